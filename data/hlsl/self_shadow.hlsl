// Phong specular lighting with a self-shadowing term, from "Implementing Lighting
// Models With HLSL" (Engel). The article prints only the pixel shader; the vertex
// shader is the specular example's, which feeds it the same TEXCOORD0..2.
// Repairs of the printed listing: the line breaks the text lost are restored.
// Compile: refx fxc /T vs_1_1 /E VS self_shadow.hlsl; refx fxc /T ps_2_0 /E PS self_shadow.hlsl
float4x4 matWorldViewProj;
float4x4 matWorld;
float4 vecLightDir;
float4 vecEye;

struct VS_OUTPUT
{
    float4 Pos : POSITION;
    float3 Light : TEXCOORD0;
    float3 Norm : TEXCOORD1;
    float3 View : TEXCOORD2;
};

VS_OUTPUT VS(float4 Pos : POSITION, float3 Normal : NORMAL)
{
    VS_OUTPUT Out = (VS_OUTPUT)0;
    Out.Pos = mul(Pos, matWorldViewProj); // transform Position
    Out.Light = vecLightDir; // L
    float3 PosWorld = normalize(mul(Pos, matWorld));
    Out.View = vecEye - PosWorld; // V
    Out.Norm = mul(Normal, matWorld); // N
    return Out;
}

float4 PS(float3 Light: TEXCOORD0, float3 Norm : TEXCOORD1, float3 View : TEXCOORD2) : COLOR
{
    float4 diffuse = { 1.0f, 0.0f, 0.0f, 1.0f};
    float4 ambient = {0.1, 0.0, 0.0, 1.0};

    float3 Normal = normalize(Norm);
    float3 LightDir = normalize(Light);
    float3 ViewDir = normalize(View);
    float4 diff = saturate(dot(Normal, LightDir)); // diffuse component

    // compute self-shadowing term
    float shadow = saturate(4* diff);

    float3 Reflect = normalize(2 * diff * Normal - LightDir); // R
    float4 specular = pow(saturate(dot(Reflect, ViewDir)), 8); // R.V^n

    // I = ambient + shadow * (Dcolor * N.L + (R.V)n)
    return ambient + shadow * (diffuse * diff + specular);
}
