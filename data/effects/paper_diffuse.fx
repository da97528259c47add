// Per-pixel diffuse bump mapping with fallbacks (seeds/000 "Hardware Shading with
// Direct3D", per-pixel lighting column: the diffuse pixel shader, "the first fallback is
// to use the D3DTOP_DOTPRODUCT3 fixed-function operator", "the second fallback is to use
// emboss bump mapping").
//   PS11      paper_diffuse.vsh + paper_diffuse_fixed.psh (the listing without the page
//             number "5 - 19" printed inside it). The shader reads c0-c3 world, c4-c7 the
//             total matrix, c16 light direction, c20 = 0.5 (the text's list says c8/c12),
//             and samples the color map in t0, the normal map in t1 (the text's Texture[]
//             list names them the other way round).
//   DOT3_VS   the text's DOTPRODUCT3 stages with the light vector from paper_diffuse.vsh:
//             needs vs.1.1 without a pixel shader (software vertex processing).
//   DOT3      the same stages with fixed-function T&L only (DX7). Approximation: without a
//             vertex shader the per-vertex tangent-space light vector cannot be made, so
//             the normal map is dotted with a constant tangent-space light in TEXTUREFACTOR
//             (vTangentLight, light from the map's north-west) and the result is modulated
//             by the color map and by per-vertex N.L from a fixed-function directional light.
//   Emboss_VS paper_emboss.vsh with the text's SelectArg1 / AddSigned(Texture|Complement)
//             stages, then a second pass multiplying in the color map lit by its oD0
//             (DESTCOLOR/SRCCOLOR, the brightening the text suggests). The shader dots the
//             light with the untransformed normal, so c0 = identity and c12 = the direction
//             toward the light in object space (exact for the unit sphere, the default
//             mesh). As printed the shader shifts oT1 away from the light along u, and
//             (its binormal is T x N, pointing to -v) toward it along v; kept as printed.
//   Emboss    the same with fixed-function T&L only (DX6). Approximation: the height map
//             is shifted by a constant texture-space offset (TextureTransform[1], from
//             vTangentLight) instead of the per-vertex tangent-space light; N.L comes from a
//             fixed-function directional light.

matrix mWorld    : WORLD;
matrix mWorldInv : WORLDINVERSE;
matrix mWVP      : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels (w = 0)
vector vHalf = {0.5, 0.5, 0.5, 0.5};
matrix mIdentity = {1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1};

// The fixed-function approximations: a light direction in tangent space (x east along u,
// y south along v, z out of the surface), pointing toward the light.
float3 vTangentLight = {-0.55, -0.45, 0.70};
// The emboss shift: 1.5 texels of the 512 x 256 height map (c24 of the sample).
float2 vEmbossOffset = {0.0029296875, 0.005859375};
DWORD  dwAmbient = 0xff202020;

texture ColorMap  < string ResourceName = "earth-color"; >;
texture NormalMap < string ResourceName = "earth-normal"; >;
texture HeightMap < string ResourceName = "earth-height"; >;

// paper_diffuse.vsh: the light vector in tangent space, biased into oD0.
vertexshader vsDiffuse =
    asm
    {
        vs.1.1
        //tranform position
        m4x4 oPos,v0,c4
        //tsb generation
        m3x3 r3,v8,c0         //gen normal
        m3x3 r5,v3,c0         //gen tangent
        //gen binormal via Cross product
        mul r0,-r3.zxyw,r5.yzxw;
        mad r4,-r3.yzxw,r5.zxyw,-r0;
        //diffuse, transform the light vector
        dp3 r6.x,r3,-c16
        dp3 r6.y,r4,-c16
        dp3 r6.z,r5,-c16
        //light in oD0
        mad oD0.xyz,r6.xyz,c20,c20   //multiply by a half then add half
        //tex coords
        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

// paper_emboss.vsh (c08 as printed).
vertexshader vsEmboss =
    asm
    {
        vs.1.1         // for emboss
        m4x4 oPos, v0,c08      // generate output position
        //diffuse
        m3x3 r3, v8, c0       // transform tan to world space
        m3x3 r5, v3, c0      // transform norm to world space
        mul r0,r3.zxyw,r5.yzxw  // cross prod to generate binormal
        mad r4,r3.yzxw,r5.zxyw,-r0
        dp3 r6.x,r3,c12      // tangent space light in r6
        dp3 r6.y,r4,c12
        //   dp3 r6.z,r5,c12  don't need this
        //                    -only x and y shifts matter
        // set up the texture, based on light direction:
        mul r1.xy,  r6.xy, -c24.xy
        mov oT0.xy, v7.xy         // copy the base height map
        add oT1.xy, v7.xy,  r1.xy    // offset the normal height map
        // simple dot product to get global darkening effects:
        dp3 oD0.xyz,v3.xyz,c12.xyz
    };

technique PS11 < string Description = "ps.1.1: dp3_sat N.L per pixel"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = <vLightDir>;
        VertexShaderConstant1[20] = <vHalf>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsDiffuse>;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0                  //sample texture
                tex t1                  //sample normal
                //diffuse
                dp3_sat r1,t1_bx2,v0_bx2         //dot(normal,light)
                //assemble final color
                mul r0,t0,    r1            //modulate against base color
            };
    }
}

technique DOT3_VS < string Description = "vs.1.1 + DOTPRODUCT3(normal map, diffuse) / MODULATE(color map)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = <vLightDir>;
        VertexShaderConstant1[20] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <ColorMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ColorOp[0]   = DotProduct3;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;

        ColorOp[1]   = Modulate;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        AlphaOp[1]   = Disable;

        ColorOp[2]   = Disable;
        AlphaOp[2]   = Disable;

        ZEnable = True;
        VertexShader = <vsDiffuse>;
        PixelShader = NULL;
    }
}

technique DOT3 < string Description = "fixed-function T&L: DOTPRODUCT3(normal map, TFACTOR) x color map x vertex N.L"; >
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader = NULL;

        Lighting = True;
        Ambient = <dwAmbient>;
        LightType[0] = Directional;
        LightDirection[0] = <vLightDir>;
        LightDiffuse[0] = {1, 1, 1, 1};
        LightSpecular[0] = {0, 0, 0, 0};
        LightAmbient[0] = {0, 0, 0, 0};
        LightEnable[0] = True;
        MaterialDiffuse = {1, 1, 1, 1};
        MaterialAmbient = {1, 1, 1, 1};

        // the biased tangent-space light: 0.5 + 0.5 l
        TextureFactor = float4(vTangentLight * 0.5 + 0.5, 1);

        Texture[0] = <NormalMap>;
        TexCoordIndex[0] = 0;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        ColorOp[0]   = DotProduct3;
        ColorArg1[0] = Texture;
        ColorArg2[0] = TFactor;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;

        Texture[1] = <ColorMap>;
        TexCoordIndex[1] = 0;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        ColorOp[1]   = Modulate;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        AlphaOp[1]   = Disable;

        // the per-vertex N.L of the light (no texture: DX7 parts have 8 blend stages)
        ColorOp[2]   = Modulate;
        ColorArg1[2] = Diffuse;
        ColorArg2[2] = Current;
        AlphaOp[2]   = Disable;

        ColorOp[3]   = Disable;
        AlphaOp[3]   = Disable;

        ZEnable = True;
    }
}

technique Emboss_VS < string Description = "vs.1.1 paper_emboss.vsh + SELECTARG1 / ADDSIGNED(height | COMPLEMENT), 2 passes"; >
{
    pass Emboss
    {
        VertexShaderConstant4[0] = <mIdentity>;
        VertexShaderConstant4[8] = <mWVP>;
        // toward the light, in object space: -(L * World^-1)
        VertexShaderConstant1[12] = -(vLightDir.x * mWorldInv[0] + vLightDir.y * mWorldInv[1] + vLightDir.z * mWorldInv[2]);
        VertexShaderConstant1[24] = float4(vEmbossOffset, 0, 0);

        Texture[0] = <HeightMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Texture;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;

        Texture[1] = <HeightMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        ColorOp[1]   = AddSigned;
        ColorArg1[1] = Texture | Complement;
        ColorArg2[1] = Current;
        AlphaOp[1]   = Disable;

        ColorOp[2]   = Disable;
        AlphaOp[2]   = Disable;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsEmboss>;
        PixelShader = NULL;
    }
    pass Color
    {
        Texture[0] = <ColorMap>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        ColorOp[1]   = Disable;
        Texture[1] = NULL;

        // 2 x src x dst
        AlphaBlendEnable = True;
        SrcBlend = DestColor;
        DestBlend = SrcColor;
        ZFunc = LessEqual;
    }
}

technique Emboss < string Description = "fixed-function T&L: SELECTARG1 / ADDSIGNED(shifted height | COMPLEMENT), 2 passes"; >
{
    pass Emboss
    {
        VertexShader = NULL;
        PixelShader = NULL;

        Lighting = True;
        Ambient = <dwAmbient>;
        LightType[0] = Directional;
        LightDirection[0] = <vLightDir>;
        LightDiffuse[0] = {1, 1, 1, 1};
        LightSpecular[0] = {0, 0, 0, 0};
        LightAmbient[0] = {0, 0, 0, 0};
        LightEnable[0] = True;
        MaterialDiffuse = {1, 1, 1, 1};
        MaterialAmbient = {1, 1, 1, 1};

        Texture[0] = <HeightMap>;
        TexCoordIndex[0] = 0;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        ColorOp[0]   = SelectArg1;
        ColorArg1[0] = Texture;
        AlphaOp[0]   = SelectArg1;
        AlphaArg1[0] = Diffuse;

        // (u, v, 1, 0) x T: the height map shifted toward the light by offset * l.xy
        // (paper_emboss.vsh shifts oT1 by the per-vertex tangent-space light instead)
        Texture[1] = <HeightMap>;
        TexCoordIndex[1] = 0;
        TextureTransformFlags[1] = Count2;
        TextureTransform[1] = float4x4(1, 0, 0, 0,
                                       0, 1, 0, 0,
                                       vEmbossOffset.x * vTangentLight.x, vEmbossOffset.y * vTangentLight.y, 1, 0,
                                       0, 0, 0, 1);
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        ColorOp[1]   = AddSigned;
        ColorArg1[1] = Texture | Complement;
        ColorArg2[1] = Current;
        AlphaOp[1]   = Disable;

        ColorOp[2]   = Disable;
        AlphaOp[2]   = Disable;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
    }
    pass Color
    {
        Texture[0] = <ColorMap>;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        ColorOp[1]   = Disable;
        Texture[1] = NULL;
        TextureTransformFlags[1] = Disable;

        // 2 x src x dst
        AlphaBlendEnable = True;
        SrcBlend = DestColor;
        DestBlend = SrcColor;
        ZFunc = LessEqual;
    }
}
