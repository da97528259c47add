// "Implementing Lighting Models With HLSL" (Engel), diffuse lighting: ambient + saturate(N.L), the normal transformed per vertex.
// The program is data/hlsl/diffuse.hlsl, included unchanged; this file adds the technique
// the article's application runs: the vertex shader for vs_1_1, the pixel shader for
// ps_2_0, and, as the article says of the programs that fit, the same pixel shader
// compiled for ps_1_4 and ps_1_1 as the fallbacks for DirectX 8 hardware. The
// application sets matWorldViewProj, matWorld, vecLightDir (toward the light) and
// vecEye by name; `refx render` binds those names the same way.
#include "../hlsl/diffuse.hlsl"

technique Diffuse
{
    pass P0
    {
        VertexShader = compile vs_1_1 VS();
        PixelShader = compile ps_2_0 PS();
    }
}

technique Diffuse_ps_1_4
{
    pass P0
    {
        VertexShader = compile vs_1_1 VS();
        PixelShader = compile ps_1_4 PS();
    }
}

technique Diffuse_ps_1_1
{
    pass P0
    {
        VertexShader = compile vs_1_1 VS();
        PixelShader = compile ps_1_1 PS();
    }
}
