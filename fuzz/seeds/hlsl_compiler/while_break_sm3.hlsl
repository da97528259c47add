float limit;
float4 main(float2 uv : TEXCOORD0) : COLOR
{
    float x = uv.x;
    int i = 0;
    [loop] while (i < 16) {
        if (x > limit) break;
        x = x * x + uv.y;
        i++;
        if (x < 0) continue;
    }
    do { x *= 0.5; } while (x > 1);
    return float4(x, i / 16.0, 0, 1);
}
