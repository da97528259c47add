// Diffuse lighting, from "Implementing Lighting Models With HLSL" (Engel).
// Repairs of the printed listing: the line breaks the text lost are restored (three
// statements were swallowed by the comments before them).
// Compile: refx fxc /T vs_1_1 /E VS diffuse.hlsl; refx fxc /T ps_2_0 /E PS diffuse.hlsl
float4x4 matWorldViewProj;
float4x4 matWorld;
float4 vecLightDir;

struct VS_OUTPUT
{
    float4 Pos : POSITION;
    float3 Light : TEXCOORD0;
    float3 Norm : TEXCOORD1;
};

VS_OUTPUT VS(float4 Pos : POSITION, float3 Normal : NORMAL)
{
    VS_OUTPUT Out = (VS_OUTPUT)0;
    Out.Pos = mul(Pos, matWorldViewProj); // transform Position
    Out.Light = vecLightDir; // output light vector
    Out.Norm = normalize(mul(Normal, matWorld)); // transform Normal and normalize it
    return Out;
}

float4 PS(float3 Light: TEXCOORD0, float3 Norm : TEXCOORD1) : COLOR
{
    float4 diffuse = { 1.0f, 0.0f, 0.0f, 1.0f};
    float4 ambient = {0.1, 0.0, 0.0, 1.0};
    return ambient + diffuse * saturate(dot(Light, Norm));
}
