void scaleBias(inout float3 v, float s, out float len2)
{
    v = v * s + 0.5;
    len2 = dot(v, v);
}
float  square(float x) { return x * x; }
float2 square(float2 x) { return x * x; }
float4 main(float4 p : POSITION) : POSITION
{
    float3 v = p.xyz;
    float l;
    scaleBias(v, 2, l);
    return float4(v * square(l), square(p.ww).x);
}
