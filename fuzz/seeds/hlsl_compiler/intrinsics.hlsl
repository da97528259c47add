float4 main(float4 a : TEXCOORD0, float4 b : TEXCOORD1) : COLOR
{
    float3 c = cross(a.xyz, b.xyz);
    float d = distance(a, b) + length(c) + atan2(a.y, a.x) + fmod(b.z, 0.5);
    float e = smoothstep(0, 1, a.w) + step(0.5, b.w) + exp(a.x) + log(abs(b.x) + 1);
    float2 sc;
    sincos(d, sc.x, sc.y);
    return float4(frac(c * e), sc.x * sc.y) + ddx(a) * 0 + any(a) + all(b);
}
