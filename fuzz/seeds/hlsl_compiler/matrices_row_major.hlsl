!row_major float4x4 m;
float3x3 rot;
float4 main(float4 p : POSITION, float3 n : NORMAL) : POSITION
{
    float4 q = mul(p, m);
    float3 r = mul(rot, n);
    float2x2 s = { 1, 2, 3, 4 };
    return q + float4(r + mul(s, q.xy).xyx, determinant(s));
}
