// Bump mapping with a gloss map, from "Implementing Lighting Models With HLSL" (Engel).
// Repairs of the printed listing:
// - the line breaks the text lost are restored;
// - the listing uses matWorldViewProj, matWorld, vecLightDir, vecEye, ColorMapSampler
//   and BumpMapSampler without declaring them: they are declared here as in the
//   earlier examples (two 2D samplers for the colour and the normal map);
// - the vertex input "float2 Tex : TEXCOORD" is kept (TEXCOORD means TEXCOORD0).
// Compile: refx fxc /T vs_1_1 /E VS bump.hlsl; refx fxc /T ps_2_0 /E PS bump.hlsl
float4x4 matWorldViewProj;
float4x4 matWorld;
float4 vecLightDir;
float4 vecEye;
sampler2D ColorMapSampler;
sampler2D BumpMapSampler;

struct VS_OUTPUT
{
    float4 Pos : POSITION;
    float2 Tex : TEXCOORD0;
    float3 Light : TEXCOORD1;
    float3 View : TEXCOORD2;
};

VS_OUTPUT VS(float4 Pos : POSITION, float2 Tex : TEXCOORD, float3 Normal : NORMAL, float3 Tangent : TANGENT )
{
    VS_OUTPUT Out = (VS_OUTPUT)0;
    Out.Pos = mul(Pos, matWorldViewProj); // transform Position

    // compute the 3x3 tranform matrix
    // to transform from world space to tangent space
    float3x3 worldToTangentSpace;
    worldToTangentSpace[0] = mul(Tangent, matWorld);
    worldToTangentSpace[1] = mul(cross(Tangent, Normal), matWorld);
    worldToTangentSpace[2] = mul(Normal, matWorld);

    Out.Tex = Tex.xy;
    Out.Light.xyz = mul(worldToTangentSpace, vecLightDir); // L
    float3 PosWorld = normalize(mul(Pos, matWorld));
    float3 Viewer = vecEye - PosWorld; // V
    Out.View = mul(worldToTangentSpace, Viewer);
    return Out;
}

float4 PS(float2 Tex: TEXCOORD0, float3 Light : TEXCOORD1, float3 View : TEXCOORD2) : COLOR
{
    float4 color = tex2D(ColorMapSampler, Tex); // fetch color map
    float3 bumpNormal = 2 * (tex2D(BumpMapSampler, Tex) - 0.5); // bump map

    float3 LightDir = normalize(Light); // L
    float3 ViewDir = normalize(View); // V

    float4 diff = saturate(dot(bumpNormal, LightDir)); // diffuse comp.

    float shadow = saturate(4 * diff); // compute self-shadowing term

    float3 Reflect = normalize(2 * diff * bumpNormal - LightDir); // R

    // gloss map in color.w restricts spec reflection
    float4 spec = min(pow(saturate(dot(Reflect, ViewDir)), 3), color.w);

    return 0.2 * color + shadow * (color * diff + spec);
}
