// RacorX6: per-pixel diffuse bump mapping (seeds/003 "Programming Pixel Shaders", RacorX6).
// Shaders: racorx6.vsh (the printed fragment completed with the oPos transform and the
// texture coordinate moves, see data/shaders/README.md), diffDot314.psh and diffDot3.psh
// verbatim. Constants as RacorX6's FrameMove sets them: c0-c3 world (transposed),
// c8-c11 world*view*projection (transposed), c12 light direction, c33 = 0.5.
// Textures as RestoreDeviceObjects binds them: stage 0 color map, stage 1 normal map.
// Techniques follow ConfirmDevice: ps.1.4 first, then ps.1.1.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels; the shader uses -c12
vector vHalf = {0.5, 0.5, 0.5, 0.5};

texture ColorMap  < string ResourceName = "earth-color"; >;
texture NormalMap < string ResourceName = "earth-normal"; >;

vertexshader vsRacorX6 =
    asm
    {
        vs.1.1
        m4x4 oPos, v0, c8

        m3x3 r5, v8, c0        ; generate tangent U
        m3x3 r7, v3, c0        ; generate normal W

        ; Cross product
        ; generate binormal V
        mul r0, r5.zxyw, -r7.yzxw;
        mad r6, r5.yzxw, -r7.zxyw,-r0;

        ;transform the light vector with U, V, W
        dp3 r8.x, r5, -c12
        dp3 r8.y, r6, -c12
        dp3 r8.z, r7, -c12

        // light -> oD0
        mad oD0.xyz, r8.xyz, c33, c33 ; multiply by a half to bias, then add half

        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

technique PS14 < string Description = "ps.1.4: diffDot314.psh"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX6>;
        PixelShader =
            asm
            {
                ps.1.4
                texld r0, t0 ; color map
                texld r1, t0 ; normal map
                dp3 r2, r1_bx2, v0_bx2 ; dot(normal, light)
                mul r0, r0, r2
            };
    }
}

technique PS11 < string Description = "ps.1.1: diffDot3.psh"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX6>;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map
                tex t1 ; normal map
                dp3 r1, t1_bx2, v0_bx2 ; dot(normal,light)
                mul r0,t0, r1 ; modulate against base color
            };
    }
}
