// The Renderman wood shader of the DirectX 9 effect white paper as an effect. The
// listing (data/hlsl/wood.fx, in the white paper's pre-release dialect, with its two
// repairs stated there) stops after the pixel shader; this file adds what the effect
// needs to run:
// - a vertex shader, WoodVS, that feeds the pixel shader its inputs: the object-space
//   position as TEXCOORD0 (the wood's solid texture coordinates, so the rings stay
//   fixed in the object), the world-space normal as TEXCOORD1 and a white COLOR0
//   (the listing scales the wood colour by its alpha);
// - the technique and its pass, which compile WoodVS for vs_2_0 and Wood for ps_2_0
//   and sample the noise volume with linear filtering.
// The listing's uniforms L (toward the light) and I (the incident view direction) are
// in world space, like the normal; the application sets them and the three colours,
// e.g. refx render wood.fx --texture noise=wood-volume --set L=-0.57,0.48,-0.67
//   --set I=0,0,1 --set ambient_color=1,1,1 --set diffuse_color=1,1,1
//   --set specular_color=1,1,1
#include "../hlsl/wood.fx"

float4x4 WoodWorldViewProj : WORLDVIEWPROJECTION;
float4x4 WoodWorld : WORLD;

struct WOOD_VS_OUTPUT
{
    float4 Position : POSITION;
    float4 Color : COLOR0;
    float3 ObjectPosition : TEXCOORD0;
    float3 Normal : TEXCOORD1;
};

WOOD_VS_OUTPUT WoodVS(float4 Position : POSITION, float3 Normal : NORMAL)
{
    WOOD_VS_OUTPUT o;
    o.Position = mul(Position, WoodWorldViewProj);
    o.Color = 1;
    o.ObjectPosition = Position.xyz;
    o.Normal = normalize(mul(Normal, (float3x3)WoodWorld));
    return o;
}

technique Wood
{
    pass P0
    {
        VertexShader = compile vs_2_0 WoodVS();
        PixelShader = compile ps_2_0 Wood();
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = None;
    }
}
