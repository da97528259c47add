sampler2D baseMap : register(s0);
sampler2D detailMap;
float blend = 0.5;
float4 main(float2 uv : TEXCOORD0, float4 c : COLOR0) : COLOR
{
    float4 a = tex2D(baseMap, uv);
    float4 b = tex2D(detailMap, uv * 4);
    return saturate(lerp(a, b, blend) * c);
}
