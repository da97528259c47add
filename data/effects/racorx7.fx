// RacorX7: per-pixel specular, N.H raised to the 16th power by four multiplies
// (seeds/003 "Programming Pixel Shaders", RacorX7; the listing's comment says 32nd).
// Vertex shader: racorx7.vsh, the printed fragment completed with the oPos transform and
// RacorX6's tangent basis (data/shaders/README.md); pixel shaders verbatim. Constants as
// RacorX6 plus the eye position in c24: c0-c3 world (transposed), c8-c11
// world*view*projection (transposed), c12 light direction, c24 eye, c33 = 0.5.
// Textures: stage 0 color map, stage 1 normal map ("the same textures and texture stage
// states as RacorX6"). ps.1.4 first, then ps.1.1.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels; the shader uses -c12
vector vEye      : CAMERAPOSITION;
vector vHalf = {0.5, 0.5, 0.5, 0.5};

texture ColorMap  < string ResourceName = "earth-color"; >;
texture NormalMap < string ResourceName = "earth-normal"; >;

vertexshader vsRacorX7 =
    asm
    {
        vs.1.1
        m4x4 oPos, v0, c8
        m3x3 r3, v8, c0                 ; generate tangent U
        m3x3 r5, v3, c0                 ; generate normal W
        mul r0, r3.zxyw, -r5.yzxw       ; generate binormal V
        mad r4, r3.yzxw, -r5.zxyw, -r0

        ; position in world space
        m4x4 r2, v0, c0

        ; get a vector toward the camera/eye
        add r2, -r2, c24

        ; normalize eye vector
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz

        add r2.xyz, r2.xyz, -c12 ; get half angle

        ; normalize half angle vector
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz

        ; transform the half angle vector into texture space
        dp3 r8.x,r3,r2
        dp3 r8.y,r4,r2
        dp3 r8.z,r5,r2

        ; half vector -> oD1
        mad oD1.xyz, r8.xyz, c33, c33 ; multiply by a half to bias, then add half

        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

technique PS14 < string Description = "ps.1.4: N.H^16 by four muls"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX7>;
        PixelShader =
            asm
            {
                ps.1.4
                texld r0, t0 ; color map
                texld r1, t1 ; normal map
                dp3 r2, r1_bx2, v1_bx2 ; dot(normal, half)

                mul r3,r2,r2 ; raise it to 32nd power
                mul r2,r3,r3
                mul r3,r2,r2
                mul r2,r3,r3

                mul r0, r0, r2
            };
    }
}

technique PS11 < string Description = "ps.1.1: N.H^16 by four muls"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX7>;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map
                tex t1 ; normal map
                dp3 r0,t1_bx2,v1_bx2; ; dot(normal,half)

                mul r1,r0,r0; ; raise it to 32nd power
                mul r0,r1,r1;
                mul r1,r0,r0;
                mul r0,r1,r1;

                ; assemble final color
                mul r0,t0,r0
            };
    }
}
