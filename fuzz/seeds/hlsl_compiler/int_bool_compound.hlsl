	int count;
float4 scale;
float4 main(float4 v : TEXCOORD0) : COLOR
{
    int n = count / 2 + 1;
    float4 r = v;
    r *= scale;
    r -= n;
    r /= 3;
    bool big = r.x > 1 && !(r.y < 0) || r.z == 2;
    int k = 7;
    k %= 3;
    k++;
    --k;
    return big ? r : r + k;
}
