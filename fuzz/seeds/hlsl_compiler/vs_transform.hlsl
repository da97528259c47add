float4x4 worldViewProj;
float4x4 world;
struct VS_OUT { float4 pos : POSITION; float3 normal : TEXCOORD1; float2 uv : TEXCOORD0; };
VS_OUT main(float4 p : POSITION, float3 n : NORMAL, float2 uv : TEXCOORD0)
{
    VS_OUT o;
    o.pos = mul(p, worldViewProj);
    o.normal = normalize(mul(n, (float3x3)world));
    o.uv = uv * 2 - 1;
    return o;
}
