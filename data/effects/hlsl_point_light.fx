// "Implementing Lighting Models With HLSL" (Engel), bump-mapped point light with attenuation 1 - saturate(dot(Att, Att)).
// The program is data/hlsl/point_light.hlsl, included unchanged; this file adds the technique
// the article's application runs: the vertex shader for vs_1_1, the pixel shader for
// ps_2_0. The application sets matWorldViewProj, matWorld, vecLightDir (toward the
// light) and vecEye by name; `refx render` binds those names the same way.
#include "../hlsl/point_light.hlsl"

technique PointLight
{
    pass P0
    {
        VertexShader = compile vs_1_1 VS();
        PixelShader = compile ps_2_0 PS();
    }
}
