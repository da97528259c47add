// Bump-mapped point light with attenuation, from "Implementing Lighting Models With
// HLSL" (Engel). The article prints only the changes to the bump-mapping example
// with "..." for the unchanged parts. Repairs:
// - the "..." are filled in with the bump-mapping example's code;
// - the line breaks the text lost are restored;
// - VS_OUTPUT gains "float3 Att : TEXCOORD3", which the vertex shader writes;
// - the vertex shader computes Out.Att from the world-space light vector before it
//   is moved to tangent space ("Out.Att = Light * LightRange" in the article names
//   the light vector Light);
// - a point light's rays "spread out from the position of the point light", so the
//   light vector is the light's position minus the surface point: vecLightDir holds
//   the light's world position here, and Light = vecLightDir.xyz - PosWorld (the
//   bump-mapping example's constant direction would give every pixel |Att| = 1,
//   attenuation 1 - 1 = 0, a black sphere);
// - "ambient", used in the last line but not declared in this example, is the 0.2
//   of the bump-mapping example's return statement (float4 ambient = 0.2).
// Compile: refx fxc /T vs_1_1 /E VS point_light.hlsl; refx fxc /T ps_2_0 /E PS point_light.hlsl
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
    float3 Att : TEXCOORD3;
};

VS_OUTPUT VS(float4 Pos : POSITION, float2 Tex : TEXCOORD, float3 Normal : NORMAL, float3 Tangent : TANGENT )
{
    VS_OUTPUT Out = (VS_OUTPUT)0;
    Out.Pos = mul(Pos, matWorldViewProj); // transform Position

    float3x3 worldToTangentSpace;
    worldToTangentSpace[0] = mul(Tangent, matWorld);
    worldToTangentSpace[1] = mul(cross(Tangent, Normal), matWorld);
    worldToTangentSpace[2] = mul(Normal, matWorld);

    Out.Tex = Tex.xy;
    float3 PosWorld = normalize(mul(Pos, matWorld));
    float3 Light = vecLightDir.xyz - PosWorld; // from the surface to the light
    Out.Light.xyz = mul(worldToTangentSpace, Light); // L
    float3 Viewer = vecEye - PosWorld; // V
    Out.View = mul(worldToTangentSpace, Viewer);

    float LightRange = 1.0; // point light
    Out.Att = Light * LightRange;
    return Out;
}

float4 PS(float2 Tex: TEXCOORD0, float3 Light : TEXCOORD1, float3 View : TEXCOORD2, float3 Att : TEXCOORD3) : COLOR
{
    float4 color = tex2D(ColorMapSampler, Tex); // fetch color map
    float3 bumpNormal = 2 * (tex2D(BumpMapSampler, Tex) - 0.5); // bump map
    float3 LightDir = normalize(Light); // L
    float3 ViewDir = normalize(View); // V
    float4 diff = saturate(dot(bumpNormal, LightDir)); // diffuse comp.
    float shadow = saturate(4 * diff); // compute self-shadowing term
    float3 Reflect = normalize(2 * diff * bumpNormal - LightDir); // R
    float4 spec = min(pow(saturate(dot(Reflect, ViewDir)), 3), color.w);
    float4 ambient = 0.2;

    // attenuation
    float4 Attenuation = mul(Att, Att);

    // colormap * (self-shadow-term * diffuse + ambient) + self-shadow-term *
    // specular
    return (color * (shadow * diff + ambient) + shadow * spec) * (1 -Attenuation);
}
