float threshold;
bool invert;
float4 main(float4 c : COLOR0, float2 uv : TEXCOORD0) : COLOR
{
    clip(c.a - threshold);
    float4 r;
    if (invert) r = 1 - c;
    else if (uv.x > 0.5) r = c.bgra;
    else r = c;
    return uv.y < 0.25 ? r * 0.5 : r;
}
