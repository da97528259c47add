// A per-pixel point light with a cube-normalized light vector, diffuse and specular
// reflection and a gloss map (seeds/002 "Advanced Shader Programming: Diffuse & Specular
// Lighting with Pixel Shaders", RacorX11-RacorX14). The article builds one effect four
// times: RacorX11 in three ps.1.1 passes, RacorX12 "implements all features of RacorX11"
// in two passes with ps.1.2, RacorX13 "creates the same effect that is shown in RacorX11
// in only one pass" with ps.1.4, and RacorX14 is "an optimized and improved version of
// RacorX13" ("If you read the article from back to front, you can see, how to divide a
// ps.1.4 shader into several ps.1.1 pixel shaders"). So one effect, techniques best first:
//   PS14      RacorX14's final shader (racorx14c_ps14.psh): one cube map stage fetched
//             twice, the half vector normalized too, five stages
//   PS14_14b  RacorX14's second shader: the half vector normalized by a second cube map stage
//   PS14_14a  RacorX14's first shader: the point light texture fetched twice (five stages)
//   PS14_13   RacorX13: one pass, six stages
//   PS12      RacorX12: Specular.psh (texdp3tex into the 2048x1 table), then the
//             attenuation multiplied in (ZERO / SRCCOLOR); the article does not print this
//             Render(): RacorX11's order with its first two passes in one
//   PS11      RacorX11: diffCubeMap.psh and specular.psh added (ONE / ONE), then the
//             attenuation multiplied in (ZERO / SRCCOLOR)
// The pixel shaders are the article's text (data/shaders/racorx1[1-4]*.psh); the vertex
// shaders of the passes are PerPixelPointLight.vsh (printed) and SpecDot3Pix.vsh /
// RacorX13's shader (not printed: data/shaders/racorx10_specular.vsh, racorx13.vsh).
// Constants as those vertex shaders read them: c0-c3 world, c8-c11 world*view*projection
// (both transposed), c12 = -(light position), c24 eye position, c33 = (1/range, 0.5, 0.5,
// 0.5); the multi-pass techniques set them in their first pass and the later passes keep
// them, as the application sets them once a frame.
// Textures: the color map (alpha = gloss), the normal map, the normalization cube map, the
// illumination map of RacorX10 (RacorX11's specular pass reads its alpha, (N.H)^16), the
// 2048x1 table of RacorX12 (A = u^16, D3DXFillTexture with LightEval), the point light
// texture (RGB = x² + y², A = z² along u) and the 1D z² map of RacorX13.
// RacorX10 (the illumination map, two ps.1.1 passes) is racorx10.fx. Nothing below ps.1.1:
// the articles' ConfirmDevice rejects devices without pixel shaders.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vEye   : CAMERAPOSITION;
// The point light (world space) and the distance over which it fades out.
vector vLightPos = {0.9, 0.8, -1.6, 1};
float  fRange = 2.6;
DWORD  BCLR = 0xff000000;    // cleared to black: the passes add and multiply into the frame buffer

texture ColorMap      < string ResourceName = "earth-color"; >;
texture NormalMap     < string ResourceName = "earth-normal"; >;
texture CubeMap       < string ResourceName = "normalization-cube"; >;
texture IllumMap      < string ResourceName = "illumination-map"; >;
texture SpecularTable < string ResourceName = "specular-table-2048"; >;
texture PointLight    < string ResourceName = "attenuation-2d"; >;
texture PointLightZ   < string ResourceName = "attenuation-1d"; >;

// PerPixelPointLight.vsh (RacorX10; "The vertex and pixel shader for the point light
// effect are the same as in RacorX10")
vertexshader vsPointLight =
    asm
    {
        vs.1.1

        ; position in clip space
        m4x4 oPos, v0, c8

        ; position in world space
        m4x4 r2, v0, c0

        ; get light vector
        add r10, r2, c12

        ; Divide each component by the range value
        mul r10, r10, c33.x

        ; multiply with 0.5 and add 0.5 to get all values in the range [0..1]
        mad r10, r10, c33.yyyy, c33.yyyy

        ; map the x and y components into the first texture
        mov oT0.xy, r10.xy

        ; z-component v0
        mov oT1.x, r10.z
    };

// PointLight.psh
pixelshader psPointLight =
    asm
    {
        ps.1.1

        tex t0
        tex t1
        add r0, 1-t0, -t1.a ; (1.0 - t0) - t1.a)
    };

// SpecDot3Pix.vsh of RacorX10-12 as data/shaders/racorx10_specular.vsh writes it: oT0, oT1
// the texture coordinates, oT2 the light vector and oT3 the half vector in texture space.
vertexshader vsSpecular =
    asm
    {
        vs.1.1
        m4x4 oPos, v0, c8
        m3x3 r3, v8, c0                ; tangent U
        m3x3 r5, v3, c0                ; normal W
        mul r0, r3.zxyw, -r5.yzxw      ; binormal V = W x U, as RacorX6
        mad r4, r3.yzxw, -r5.zxyw, -r0
        m4x4 r2, v0, c0                ; position in world space
        add r10, -r2, -c12             ; light vector: light position - position
        dp3 r11.x, r10.xyz, r10.xyz
        rsq r11.xyz, r11.x
        mul r10.xyz, r10.xyz, r11.xyz  ; normalized L
        add r2, -r2, c24               ; vector toward the eye
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz
        add r2.xyz, r2.xyz, r10.xyz    ; half angle
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz    ; normalized H
        dp3 oT2.x, r3, r10             ; L in texture space
        dp3 oT2.y, r4, r10
        dp3 oT2.z, r5, r10
        dp3 oT3.x, r3, r2              ; H in texture space
        dp3 oT3.y, r4, r2
        dp3 oT3.z, r5, r2
        mov oT0.xy, v7.xy
        mov oT1.xy, v7.xy
    };

// RacorX13's vertex shader (racorx13.vsh, written from the article's description: the two
// vertex shaders of RacorX12 in one): oT0 texture coordinates, oT1 light vector, oT2 half
// vector (texture space), oT4.xy / oT5.x the attenuation coordinates.
vertexshader vsRacorX13 =
    asm
    {
        vs.1.1
        m4x4 oPos, v0, c8
        m3x3 r3, v8, c0                ; tangent U
        m3x3 r5, v3, c0                ; normal W
        mul r0, r3.zxyw, -r5.yzxw      ; binormal V = W x U, as RacorX6
        mad r4, r3.yzxw, -r5.zxyw, -r0
        m4x4 r2, v0, c0                ; position in world space
        add r10, -r2, -c12             ; light vector: light position - position
        dp3 r11.x, r10.xyz, r10.xyz
        rsq r11.xyz, r11.x
        mul r10.xyz, r10.xyz, r11.xyz  ; normalized L
        add r2, -r2, c24               ; vector toward the eye
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz
        add r2.xyz, r2.xyz, r10.xyz    ; half angle
        dp3 r11.x, r2.xyz, r2.xyz
        rsq r11.xyz, r11.x
        mul r2.xyz, r2.xyz, r11.xyz    ; normalized H
        dp3 oT1.x, r3, r10             ; L in texture space
        dp3 oT1.y, r4, r10
        dp3 oT1.z, r5, r10
        dp3 oT2.x, r3, r2              ; H in texture space
        dp3 oT2.y, r4, r2
        dp3 oT2.z, r5, r2
        m4x4 r2, v0, c0                ; attenuation, as racorx10_pointlight.vsh
        add r9, r2, c12
        mul r9, r9, c33.x
        mad r9, r9, c33.yyyy, c33.yyyy
        mov oT4.xy, r9.xy
        mov oT5.x, r9.z
        mov oT0.xy, v7.xy
    };

technique PS14 < string Description = "RacorX14, ps.1.4, one pass: the cube map stage fetched twice, half vector normalized (five stages)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        // stage 0 normal map, 2 color map, 3 specular table, 4 point light texture, 5 cube map (stage 1 unused)
        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = NULL;
        Texture[2] = <ColorMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = Linear;
        AddressU[2] = Wrap; AddressV[2] = Wrap;
        Texture[3] = <SpecularTable>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;
        Texture[4] = <PointLight>;
        MinFilter[4] = Linear; MagFilter[4] = Linear; MipFilter[4] = None;
        AddressU[4] = Clamp; AddressV[4] = Clamp;
        Texture[5] = <CubeMap>;
        MinFilter[5] = Linear; MagFilter[5] = Linear; MipFilter[5] = None;
        AddressU[5] = Clamp; AddressV[5] = Clamp; AddressW[5] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsRacorX13>;
        PixelShader =
            asm
            {
                ; t0 - coordinates color map
                ; t1 - light vector
                ; t2 - half vector
                ; t3 - unused
                ; t4 - coordinates 2D attenuation map
                ; t5 - coordinates 1D attenuation map
                ps.1.4
                texld r0, t0 ; normal map
                texld r5, t2 ; cube map for half angle vector
                texld r4, t5 ; attenuation 1D map

                dp3 r5.rgb, r5, r0_bx2 ; specular

                mov r1.r, r4.a

                phase

                texld r2, t0 ; color map
                texld r3, r5 ; samples specular value from specular map
                texld r4, t4 ; attenuation 2D map
                texld r5, t1 ; cube map for light vector

                dp3 r5.rgb, r5_bx2, r0_bx2 ; diffuse

                add r4, 1-r4, -r1.r ; (1.0 - 2Dvalue) - dest

                mul r1.a, r2.a, r3.a ; (N dot H)^16 * gloss value
                +mul r1.rgb, r5, r2 ; diffuse * color
                add r3, r1.a, r1 ; ((N dot H)^16 * gloss value) + (diffuse * color)
                mul r0, r3, r4 ; attenuation
            };
    }
}

technique PS14_14b < string Description = "RacorX14 second shader, ps.1.4, one pass: the half vector normalized by the cube map in a second stage"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        // stage 0 normal map, 1 cube map, 2 color map, 3 specular table, 4 point light texture, 5 the cube map again
        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = <CubeMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp; AddressW[1] = Clamp;
        Texture[2] = <ColorMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = Linear;
        AddressU[2] = Wrap; AddressV[2] = Wrap;
        Texture[3] = <SpecularTable>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;
        Texture[4] = <PointLight>;
        MinFilter[4] = Linear; MagFilter[4] = Linear; MipFilter[4] = None;
        AddressU[4] = Clamp; AddressV[4] = Clamp;
        Texture[5] = <CubeMap>;
        MinFilter[5] = Linear; MagFilter[5] = Linear; MipFilter[5] = None;
        AddressU[5] = Clamp; AddressV[5] = Clamp; AddressW[5] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsRacorX13>;
        PixelShader =
            asm
            {
                ; t0 - coordinates color map
                ; t1 - light vector
                ; t2 - half vector
                ; t3 - unused
                ; t4 - coordinates 2D attenuation map
                ; t5 - coordinates 1D attenuation map
                ps.1.4
                texld r1, t1 ; cube map for light vector
                texld r0, t0 ; normal map
                texld r5, t2 ; cube map for half angle vector
                texld r4, t5 ; attenuation 1D map

                dp3 r1.rgb, r1_bx2, r0_bx2 ; diffuse
                dp3 r5.rgb, r5, r0_bx2 ; specular

                mov r0.r, r4.a

                phase

                texld r2, t0 ; color map
                texld r3, r5 ; samples specular value from specular map
                texld r4, t4 ; attenuation 2D map

                add r0, 1-r4, -r0.r ; (1.0 - 2Dvalue) - dest

                mul r1.a, r2.a, r3.a ; (N dot H)^16 * gloss value
                +mul r1.rgb, r1, r2 ; diffuse * color
                add r5, r1.a, r1 ; ((N dot H)^16 * gloss value) + (diffuse * color)
                mul r0, r5, r0 ; attenuation
            };
    }
}

technique PS14_14a < string Description = "RacorX14 first shader, ps.1.4, one pass: the point light texture fetched twice (five stages)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        // stage 0 normal map, 1 cube map, 2 color map, 3 specular table, 4 point light texture (read with t5 and t4)
        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = <CubeMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp; AddressW[1] = Clamp;
        Texture[2] = <ColorMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = Linear;
        AddressU[2] = Wrap; AddressV[2] = Wrap;
        Texture[3] = <SpecularTable>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;
        Texture[4] = <PointLight>;
        MinFilter[4] = Linear; MagFilter[4] = Linear; MipFilter[4] = None;
        AddressU[4] = Clamp; AddressV[4] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsRacorX13>;
        PixelShader =
            asm
            {
                ; t0 - coordinates color map
                ; t1 - light vector
                ; t2 - half vector
                ; t3 - unused
                ; t4 - coordinates 2D attenuation map
                ; t5 - coordinates 1D attenuation map
                ps.1.4
                texld r1, t1 ; cube map
                texld r0, t0 ; normal map
                texcrd r3.rgb, t2 ; half angle vector
                texld r4, t5 ; attenuation 1D map

                dp3 r1.rgb, r1_bx2, r0_bx2 ; diffuse
                dp3 r5.rgb, r3, r0_bx2 ; specular

                mov r0.r, r4.a

                phase

                texld r2, t0 ; color map + specular map
                texld r3, r5 ; samples specular value from specular map
                texld r4, t4 ; attenuation 2D map

                add r0, 1-r4, -r0.r ; (1.0 - 2Dvalue) - dest

                mul r1.a, r2.a, r3.a ; (N dot H)^16 * gloss value
                +mul r1.rgb, r1, r2 ; diffuse * color
                add r5, r1.a, r1 ; ((N dot H)^16 * gloss value) + (diffuse * color)
                mul r0, r5, r0 ; attenuation
            };
    }
}

technique PS14_13 < string Description = "RacorX13, ps.1.4, one pass, six stages"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        // stage 0 normal map, 1 cube map, 2 color map, 3 specular table, 4 point light texture, 5 the 1D attenuation map
        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = <CubeMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp; AddressW[1] = Clamp;
        Texture[2] = <ColorMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = Linear;
        AddressU[2] = Wrap; AddressV[2] = Wrap;
        Texture[3] = <SpecularTable>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;
        Texture[4] = <PointLight>;
        MinFilter[4] = Linear; MagFilter[4] = Linear; MipFilter[4] = None;
        AddressU[4] = Clamp; AddressV[4] = Clamp;
        Texture[5] = <PointLightZ>;
        MinFilter[5] = Linear; MagFilter[5] = Linear; MipFilter[5] = None;
        AddressU[5] = Clamp; AddressV[5] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsRacorX13>;
        PixelShader =
            asm
            {
                ; t0 - coordinates color map
                ; t1 - light vector
                ; t2 - half vector
                ; t3 - unused
                ; t4 - coordinates 2D attenuation map
                ; t5 - coordinates 1D attenuation map
                ps.1.4
                texld r1, t1 ; cube map
                texld r0, t0 ; normal map
                texcrd r3.rgb, t2 ; half angle vector

                dp3 r1.rgb, r1_bx2, r0_bx2 ; diffuse
                dp3 r4.rgb, r3, r0_bx2 ; specular

                phase

                texld r2, t0 ; color map
                texld r3, r4 ; samples specular value from specular map
                texld r4, t4 ; attenuation 2D map
                texld r5, t5 ; attenuation 1D map
                add r5, 1-r4, -r5.a ; (1.0 - 2Dvalue) - dest

                mul r1.a, r2.a, r3.a ; (N dot H)^16 * gloss value
                +mul r1.rgb, r1, r2 ; diffuse * color
                add r0, r1.a, r1 ; ((N dot H)^16 * gloss value) + (diffuse * color)
                mul r0, r0, r5 ; attenuation
            };
    }
}

technique PS12 < string Description = "RacorX12, ps.1.2, 2 passes: Specular.psh (texdp3tex), then the attenuation (ZERO / SRCCOLOR)"; >
{
    pass DiffuseSpecular
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        AddressU[1] = Wrap; AddressV[1] = Wrap;
        Texture[2] = <CubeMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp; AddressW[2] = Clamp;
        Texture[3] = <SpecularTable>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        VertexShader = <vsSpecular>;
        PixelShader =
            asm
            {
                ps.1.2
                tex t0 ; color map + gloss map
                tex t1 ; normal map
                tex t2 ; cube map
                texdp3tex t3, t1_bx2 ; t3.a = (N dot H)^16
                dp3 r0, t2_bx2, t1_bx2 ; diffuse
                mul r1.rgb, t0, r0 ; diffuse * color
                +mul r1.a, t0.a, t3.a ; (N dot H)^16 * gloss value
                add r0, r1, r1.a
            };
    }
    pass Attenuation
    {
        // SrcColor * 0 + DestColor * SrcColor
        AlphaBlendEnable = True;
        SrcBlend = Zero;
        DestBlend = SrcColor;

        Texture[0] = <PointLight>;
        Texture[1] = <PointLight>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = None;
        AddressU[0] = Clamp; AddressV[0] = Clamp;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp;

        PixelShader = <psPointLight>;
        VertexShader = <vsPointLight>;
    }
}

technique PS11 < string Description = "RacorX11, ps.1.1, 3 passes: diffuse with the cube map, specular (ONE / ONE), attenuation (ZERO / SRCCOLOR)"; >
{
    // first pass: diffuse(cubemap) * color
    pass Diffuse
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        AlphaBlendEnable = True;
        // SrcColor * 1 + DestColor * 1
        SrcBlend = One;
        DestBlend = One;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        AddressU[1] = Wrap; AddressV[1] = Wrap;
        Texture[2] = <CubeMap>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp; AddressW[2] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map
                tex t1 ; normal map
                tex t2 ; cube map

                dp3 r1, t2_bx2, t1_bx2 ; diffuse
                mul r0, t0, r1
            };
        VertexShader = <vsSpecular>;
    }
    // second pass: specular. "The same vertex shader is used for the first and the second
    // pass, although it is explicitly set only in the first pass."
    pass Specular
    {
        Texture[3] = <IllumMap>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;
        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map + gloss map
                tex t1 ; normal map
                texm3x2pad t2, t1_bx2 ; u = t1 dot (t2) half vector
                texm3x2tex t3, t1_bx2 ; v = t1 dot (t3) half vector
                ; fetch texture 4 at u, v
                ; t3.a = (N dot H)^16
                mul r0, t0.a, t3.a ; (N dot H)^16 * gloss value
            };
    }
    // third pass: attenuation
    pass Attenuation
    {
        // SrcColor * 0 + DestColor * SrcColor
        SrcBlend = Zero;
        DestBlend = SrcColor;

        Texture[0] = <PointLight>;
        Texture[1] = <PointLight>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = None;
        AddressU[0] = Clamp; AddressV[0] = Clamp;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp;

        // Set the pixel shader
        PixelShader = <psPointLight>;
        // set vertex shader
        VertexShader = <vsPointLight>;
    }
}
