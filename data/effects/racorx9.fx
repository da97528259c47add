// RacorX9: per-pixel diffuse + specular (seeds/003 "Programming Pixel Shaders", RacorX9).
// Vertex shaders: racorx9_ps14.vsh (SpecDot314) and racorx9.vsh (SpecDot3Pix), the printed
// fragments completed with the oPos transform, RacorX6's tangent basis and light vector
// (data/shaders/README.md); pixel shaders verbatim. Constants: c0-c3 world (transposed),
// c8-c11 world*view*projection (transposed), c12 light direction, c24 eye, c33 = 0.5.
// Stage 0 color map, stage 1 normal map. The ps.1.4 shader reads the specular power from
// the normal map's alpha ("the values of this map are stored in the alpha values of the
// normal map"): the built-in earth-normal-specular is earth-normal with alpha =
// pow((y + 0.5) / height, 16), RacorX8's LightEval table.
// Techniques: the ps.1.4 table shader, the text's "equivalent to the ps.1.1 shader" in
// ps.1.4 (never chosen before PS11 by a ps.1.4 part; pick it with --technique), ps.1.1.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels; the shaders use -c12
vector vEye      : CAMERAPOSITION;
vector vHalf = {0.5, 0.5, 0.5, 0.5};

texture ColorMap          < string ResourceName = "earth-color"; >;
texture NormalMap         < string ResourceName = "earth-normal"; >;
texture NormalMapSpecular < string ResourceName = "earth-normal-specular"; >;

// SpecDot3Pix.vsh: light vector in oD0, half vector in oD1 (ps.1.1 and the mul version).
vertexshader vsSpecDot3Pix =
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

        ; half vector -> oD1 ps.1.1
        mad oD1.xyz, r8, c33, c33 ; multiply by a half to bias, then add half

        dp3 r8.x, r3, -c12              ; transform the light vector with U, V, W
        dp3 r8.y, r4, -c12
        dp3 r8.z, r5, -c12
        ; light -> oD0
        mad oD0.xyz, r8.xyz, c33, c33 ; multiply a half to bias, then add half

        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

// SpecDot314.vsh: light vector in oD0, half vector in oT2/oT3.
vertexshader vsSpecDot314 =
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

        ; half vector -> oT2/oT3 ps.1.4
        mad oT2.xyz, r8, c33, c33 ; multiply by a half to bias, then add half
        mad oT3.xyz, r8, c33, c33 ; multiply by a half to bias, then add half

        dp3 r8.x, r3, -c12              ; transform the light vector with U, V, W
        dp3 r8.y, r4, -c12
        dp3 r8.z, r5, -c12
        ; light -> oD0
        mad oD0.xyz, r8.xyz, c33, c33 ; multiply a half to bias, then add half

        mov oT0.xy, v7.xy
    };

technique PS14 < string Description = "ps.1.4: specular power from the normal map's alpha"; >
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
        // Read a second time at (N.H, N.H): clamped like RacorX8's table, or N.H near 1
        // would wrap onto the table's dark first row.
        Texture[1] = <NormalMapSpecular>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        AddressU[1] = Clamp; AddressV[1] = Clamp;

        ZEnable = True;
        VertexShader = <vsSpecDot314>;
        PixelShader =
            asm
            {
                ; specular power from a lookup table
                ps.1.4
                ; r1 holds normal map
                ; t0 holds texture coordinates for normal and color map
                ; t2 holds half angle vector
                ; r0 holds color map
                texld r1, t0
                texcrd r4.rgb, t2

                dp3 r4.rg, r4_bx2, r1_bx2 ; (N dot H)
                mov r2, r1 ; save normal map data to r2
                phase
                texld r0, t0
                texld r1, r4 ; samples specular value from normal map with u,v
                dp3 r3, r2_bx2, v0_bx2 ; dot(normal,light)
                mad r0, r0, r3, r1.a
            };
    }
}

technique PS14Mul < string Description = "ps.1.4: the text's equivalent of the ps.1.1 shader"; >
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
        VertexShader = <vsSpecDot3Pix>;
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

                dp3 r1, r1_bx2, v0_bx2 ; dot(normal,light)
                mad r0, r0, r1, r2
            };
    }
}

technique PS11 < string Description = "ps.1.1: diffuse + N.H^16 by four muls"; >
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
        VertexShader = <vsSpecDot3Pix>;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map
                tex t1 ; normal map
                dp3 r0,t1_bx2,v1_bx2 ; dot(normal,half)

                mul r1,r0,r0; ; raise it to 32nd power
                mul r0,r1,r1;
                mul r1,r0,r0;
                mul r0,r1,r1;

                dp3 r1, t1_bx2, v0_bx2 ; dot(normal,light)
                mad r0, t0, r1, r0
            };
    }
}
