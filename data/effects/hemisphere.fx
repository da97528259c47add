// Hemisphere lighting, the "DIY" lighting model of seeds/000 "Hardware Shading with
// Direct3D" (Custom Per-Pixel Lighting): the sky and the ground as two hemispherical
// lights, color = a * SkyColor + (1 - a) * GroundColor, a = 0.5 + 0.5 cos(q) with q the
// angle between the normal and the sky axis (the 2-term model, Figure 19); times the open
// fraction of the hemisphere (the occlusion term: the 3-term model, Figure 21); plus a
// directional light ("Finally, combine this with a directional light", Figure 22).
// Techniques best first:
//   PixelSun     per pixel, 3-term + the directional light. The fragment below with two
//                lines added: the occlusion from the normal map's alpha ("pixel-to-pixel by
//                firing rays in a height field and storing the result in the alpha channel
//                of a normal map": built-in "earth-normal-occlusion", D3DXComputeNormalMap
//                with COMPUTE_OCCLUSION) and N.L of the light, whose tangent-space direction
//                the vertex shader (paper_diffuse.vsh with four lines added) puts in oD1.
//   Pixel3Term   per pixel, 3-term: the fragment times the normal map's alpha.
//   Pixel        the per-pixel fragment as printed (hemisphere_fixed.psh: the listing with
//                its missing "ps.1.1"), 2-term: "pass the hemisphere axis in as a light
//                direction and use the standard tangent space basis vertex shader"
//                (paper_diffuse.vsh with c16 = -axis). Its dp3_d2_sat clamps the lower
//                hemisphere to a = 0.5, as printed.
//   VertexSun    per vertex, 3-term + the directional light: hemisphere.vsh with the light's
//                N.L added (lines marked "; +").
//   Vertex       the vertex hemisphere shader as printed (hemisphere.vsh), 3-term: the
//                occluded fraction comes in v7.z (built-in mesh "teapot-occlusion").
//   Vertex2Term  hemisphere.vsh without its two occlusion lines.
//   Integral     DirectX 7 fixed function: "Integrating the environment map to get that term
//                is the usual technique. This will work even on DirectX 7-class hardware."
//                The integral of the two-color environment, a = 1 - 0.5 sin(q) (q < 90°),
//                0.5 sin(q) (q > 90°), baked into a cube map at authoring time (built-in
//                "hemisphere-integral", sky along +y, the colors below), looked up with the
//                camera-space normal turned back into world space by the inverse view
//                rotation, times the color map. 2-term: the colors cannot change at run time
//                ("the integral could not change during the game").
// The vertex techniques write only oD0: the fixed-function stage passes the diffuse color
// through, as the vertex shader leaves texturing to the application.
// Constants: per pixel (paper_diffuse.vsh) c0-c3 world, c4-c7 total matrix (transposed),
// c16 = -(sky axis), c20 = 0.5, c12 the light's direction; ps c1 sky color, c2 ground
// color, c3 the light's color, c5 = 0.5. Per vertex (hemisphere.vsh) c0-c3 world, c8-c11
// total matrix, c33 = 0.5, c40 sky vector, c41 sky color, c42 ground color, c43 the
// intensity, c44 = (1, 1, 1, 1), and for VertexSun c45 toward the light, c46 its color,
// c47 = 0.

matrix mWorld    : WORLD;
matrix mWVP      : WORLDVIEWPROJECTION;
matrix mViewInv  : VIEWINVERSE;
vector vLightDir : LIGHTDIRECTION;     // the directional light: the direction it travels
vector vSkyAxis = {0, 1, 0, 0};        // up
vector cSky     = {0.55, 0.7, 1.0, 1};
vector cGround  = {0.35, 0.25, 0.15, 1};
vector cSun     = {0.55, 0.5, 0.4, 1};
vector cIntensity = {1, 1, 1, 1};
vector vHalf = {0.5, 0.5, 0.5, 0.5};
vector vOne  = {1, 1, 1, 1};
vector vZero = {0, 0, 0, 0};

texture ColorMap    < string ResourceName = "earth-color"; >;
texture NormalMap   < string ResourceName = "earth-normal-occlusion"; >;   // alpha = open sky
textureCUBE IntegralMap < string ResourceName = "hemisphere-integral"; >;

// paper_diffuse.vsh: the hemisphere axis (-c16) in tangent space, biased into oD0.
vertexshader vsPixel =
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

// The same with the directional light (-c12) in tangent space in oD1.
vertexshader vsPixelSun =
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
        dp3 r7.x,r3,-c12             ; + the directional light in tangent space
        dp3 r7.y,r4,-c12             ; +
        dp3 r7.z,r5,-c12             ; +
        mad oD1.xyz,r7.xyz,c20,c20   ; + biased into oD1
        //tex coords
        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

// hemisphere.vsh
vertexshader vsVertex =
    asm
    {
        vs.1.1         // vertex hemisphere shader
        m4x4 oPos,v0,c8   // transform position
        m3x3 r0, v3,c0   // transform normal
        dp3 r0,r0,c40   // c40 is sky vector
        mov r1,c33      // c33 is .5f in all channels
        mad r0,r0,c33,r1   // bias operation
        mov r1,c42      // c42 is ground color
        sub r1,c41,r1      // c41 is sky color
        mad r0,r1,r0,c42   // lerp operation
        //c44 = (1,1,1,1)
        sub r1,c44,v7.zzz   // v7.zzz = occlusion term
        mul r0,r0,r1
        mul oD0,r0,c43
    };

technique PixelSun < string Description = "ps.1.1: hemisphere x open sky (normal map alpha) + directional light, per pixel"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[16] = -vSkyAxis;
        VertexShaderConstant1[20] = <vHalf>;
        PixelShaderConstant1[1] = <cSky>;
        PixelShaderConstant1[2] = <cGround>;
        PixelShaderConstant1[3] = <cSun>;
        PixelShaderConstant1[5] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <ColorMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsPixelSun>;
        PixelShader =
            asm
            {
                ps.1.1
                //   v0.rgb is hemi axis in tangent space
                //   v1.rgb is the directional light in tangent space
                tex t0         // normal map, alpha = open fraction of the sky
                tex t1         // base texture
                dp3_d2_sat r0,v0_bx2,t0_bx2   // dot normal with hemi axis
                add r0,r0,c5      // map into range, not _sat
                lrp r0,r0,c1,c2
                mul r0,r0,t0.a    // occlusion term
                dp3_sat r1,v1_bx2,t0_bx2      // dot normal with the light
                mad r0,r1,c3,r0   // add the directional light
                mul r0,r0,t1      // modulate base texture
            };
    }
}

technique Pixel3Term < string Description = "ps.1.1: hemisphere x open sky (normal map alpha), per pixel"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = -vSkyAxis;
        VertexShaderConstant1[20] = <vHalf>;
        PixelShaderConstant1[1] = <cSky>;
        PixelShaderConstant1[2] = <cGround>;
        PixelShaderConstant1[5] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <ColorMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsPixel>;
        PixelShader =
            asm
            {
                ps.1.1
                //   v0.rgb is hemi axis in tangent space
                tex t0         // normal map, alpha = open fraction of the sky
                tex t1         // base texture
                dp3_d2_sat r0,v0_bx2,t0_bx2   // dot normal with hemi axis
                add r0,r0,c5      // map into range, not _sat
                lrp r0,r0,c1,c2
                mul r0,r0,t0.a    // occlusion term
                mul r0,r0,t1      // modulate base texture
            };
    }
}

technique Pixel < string Description = "ps.1.1: the per-pixel fragment as printed (2-term)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = -vSkyAxis;
        VertexShaderConstant1[20] = <vHalf>;
        PixelShaderConstant1[1] = <cSky>;
        PixelShaderConstant1[2] = <cGround>;
        PixelShaderConstant1[5] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <ColorMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsPixel>;
        PixelShader =
            asm
            {
                ps.1.1
                //   v0.rgb is hemi axis in tangent space
                // v0.a is occlusion ratio from vshader
                tex t0         // normal map
                tex t1         // base texture
                dp3_d2_sat r0,v0_bx2,t0_bx2   // dot normal with hemi axis
                add r0,r0,c5      // map into range, not _sat
                lrp r0,r0,c1,c2
                mul r0,r0,t1      // modulate base texture
            };
    }
}

technique VertexSun < string Description = "vs.1.1: hemisphere x (1 - occlusion) + directional light, per vertex"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[33] = <vHalf>;
        VertexShaderConstant1[40] = <vSkyAxis>;
        VertexShaderConstant1[41] = <cSky>;
        VertexShaderConstant1[42] = <cGround>;
        VertexShaderConstant1[43] = <cIntensity>;
        VertexShaderConstant1[44] = <vOne>;
        VertexShaderConstant1[45] = -vLightDir;
        VertexShaderConstant1[46] = <cSun>;
        VertexShaderConstant1[47] = <vZero>;

        Texture[0] = NULL;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
        ColorOp[1] = Disable;    AlphaOp[1] = Disable;

        ZEnable = True;
        PixelShader = NULL;
        VertexShader =
            asm
            {
                vs.1.1         // vertex hemisphere shader
                m4x4 oPos,v0,c8   // transform position
                m3x3 r0, v3,c0   // transform normal
                dp3 r2,r0,c45    ; + c45 is the direction toward the light
                max r2,r2,c47    ; + N.L, not below c47 = 0
                dp3 r0,r0,c40   // c40 is sky vector
                mov r1,c33      // c33 is .5f in all channels
                mad r0,r0,c33,r1   // bias operation
                mov r1,c42      // c42 is ground color
                sub r1,c41,r1      // c41 is sky color
                mad r0,r1,r0,c42   // lerp operation
                //c44 = (1,1,1,1)
                sub r1,c44,v7.zzz   // v7.zzz = occlusion term
                mul r0,r0,r1
                mad r0,r2,c46,r0 ; + c46 is the light's color
                mul oD0,r0,c43
            };
    }
}

technique Vertex < string Description = "vs.1.1: the vertex hemisphere shader as printed (3-term)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[33] = <vHalf>;
        VertexShaderConstant1[40] = <vSkyAxis>;
        VertexShaderConstant1[41] = <cSky>;
        VertexShaderConstant1[42] = <cGround>;
        VertexShaderConstant1[43] = <cIntensity>;
        VertexShaderConstant1[44] = <vOne>;

        Texture[0] = NULL;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
        ColorOp[1] = Disable;    AlphaOp[1] = Disable;

        ZEnable = True;
        PixelShader = NULL;
        VertexShader = <vsVertex>;
    }
}

technique Vertex2Term < string Description = "vs.1.1: the vertex hemisphere shader without the occlusion term"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[33] = <vHalf>;
        VertexShaderConstant1[40] = <vSkyAxis>;
        VertexShaderConstant1[41] = <cSky>;
        VertexShaderConstant1[42] = <cGround>;
        VertexShaderConstant1[43] = <cIntensity>;

        Texture[0] = NULL;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
        ColorOp[1] = Disable;    AlphaOp[1] = Disable;

        ZEnable = True;
        PixelShader = NULL;
        VertexShader =
            asm
            {
                vs.1.1         // vertex hemisphere shader
                m4x4 oPos,v0,c8   // transform position
                m3x3 r0, v3,c0   // transform normal
                dp3 r0,r0,c40   // c40 is sky vector
                mov r1,c33      // c33 is .5f in all channels
                mad r0,r0,c33,r1   // bias operation
                mov r1,c42      // c42 is ground color
                sub r1,c41,r1      // c41 is sky color
                mad r0,r1,r0,c42   // lerp operation
                mul oD0,r0,c43
            };
    }
}

technique Integral < string Description = "fixed function (DirectX 7): the hemisphere's integral in a cube map, looked up with the normal"; >
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader = NULL;
        Lighting = False;

        Texture[0] = <IntegralMap>;
        // the camera-space normal, turned into world space by the inverse view rotation
        TexCoordIndex[0] = CameraSpaceNormal;
        TextureTransform[0] = float4x4(mViewInv[0].xyz, 0, mViewInv[1].xyz, 0, mViewInv[2].xyz, 0, 0, 0, 0, 1);
        TextureTransformFlags[0] = Count3;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = None;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Texture;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Texture;

        Texture[1] = <ColorMap>;
        TexCoordIndex[1] = 0;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        ColorOp[1] = Modulate; ColorArg1[1] = Texture; ColorArg2[1] = Current;
        AlphaOp[1] = Disable;
        ColorOp[2] = Disable;  AlphaOp[2] = Disable;

        ZEnable = True;
    }
}
