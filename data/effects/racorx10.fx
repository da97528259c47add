// RacorX10: a per-pixel point light with an attenuation map, and diffuse and specular
// reflection read from an illumination map (seeds/002 "Advanced Shader Programming:
// Diffuse & Specular Lighting with Pixel Shaders", RacorX10, "Two Passes").
//   pass Attenuation  PerPixelPointLight.vsh / PointLight.psh (verbatim): 1 - (x² + y² + z²)
//                     of the light vector divided by the range, from the point light
//                     texture in stages 0 and 1 (RGB = x² + y², A = z² read along u).
//   pass Illumination SpecDot3Pix.vsh (not printed; racorx10_specular.vsh, written from
//                     its description) / SpecDot3.psh (verbatim): texm3x2pad/texm3x2tex
//                     look up the illumination map at (N.L, N.H): RGB = N.L, A = (N.H)^16;
//                     color * N.L + gloss * (N.H)^16, multiplied into the first pass
//                     ("SrcColor * 0 + DestColor * SrcColor": SRCBLEND ZERO, DESTBLEND SRCCOLOR).
// Constants as the article's vertex shaders read them: c0-c3 world, c8-c11
// world*view*projection (both transposed), c12 = -(light position) ("add r10, r2, c12"
// gives position - light), c24 eye position, c33 = (1/range, 0.5, 0.5, 0.5). They are set
// once in the first pass and kept by the second, as the application sets them once a frame.
// Textures: stage 0 color map (alpha = gloss), 1 normal map, 3 illumination map
// (diffspec.dds: built-in "illumination-map"), the point light texture (pointlight.dds:
// "attenuation-2d") in stages 0 and 1 of the first pass.
// One technique: ps.1.1, the version the article's ConfirmDevice asks for. The same
// lighting with a cube-normalized light vector and its ps.1.2 and ps.1.4 versions
// (RacorX11-14) is racorx_point_light.fx.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vEye   : CAMERAPOSITION;
// The point light (world space) and the distance over which it fades out.
vector vLightPos = {0.9, 0.8, -1.6, 1};
float  fRange = 2.6;
DWORD  BCLR = 0xff000000;    // cleared to black: the passes multiply into the frame buffer

texture ColorMap   < string ResourceName = "earth-color"; >;
texture NormalMap  < string ResourceName = "earth-normal"; >;
texture IllumMap   < string ResourceName = "illumination-map"; >;
texture PointLight < string ResourceName = "attenuation-2d"; >;

// PerPixelPointLight.vsh
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

// SpecDot3Pix.vsh as data/shaders/racorx10_specular.vsh writes it: oT0, oT1 the texture
// coordinates, oT2 the light vector and oT3 the half vector in texture space.
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

// PointLight.psh
pixelshader psPointLight =
    asm
    {
        ps.1.1

        tex t0
        tex t1
        add r0, 1-t0, -t1.a ; (1.0 - t0) - t1.a)
    };

technique PS11 < string Description = "ps.1.1, 2 passes: attenuation (PointLight.psh), then SpecDot3.psh multiplied in (ZERO / SRCCOLOR)"; >
{
    pass Attenuation
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = -vLightPos;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = float4(1 / fRange, 0.5, 0.5, 0.5);

        // first pass attenuation
        Texture[0] = <PointLight>;
        Texture[1] = <PointLight>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = None;
        AddressU[0] = Clamp; AddressV[0] = Clamp;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;
        AddressU[1] = Clamp; AddressV[1] = Clamp;

        ZEnable = True;
        ZFunc = LessEqual;
        AlphaBlendEnable = False;
        PixelShader = <psPointLight>;
        VertexShader = <vsPointLight>;
    }
    pass Illumination
    {
        AlphaBlendEnable = True;
        // SrcColor * 0 + DestColor * SrcColor
        SrcBlend = Zero;
        DestBlend = SrcColor;

        // second pass
        Texture[0] = <ColorMap>;
        Texture[1] = <NormalMap>;
        Texture[3] = <IllumMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        AddressU[0] = Wrap; AddressV[0] = Wrap;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;
        AddressU[1] = Wrap; AddressV[1] = Wrap;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = None;
        AddressU[3] = Clamp; AddressV[3] = Clamp;

        PixelShader =
            asm
            {
                ps.1.1
                tex t0 ; color map in t0.rgb + gloss map in t0.a
                tex t1 ; normal map
                texm3x2pad t2, t1_bx2 ; u = t1 dot (t2) light vector
                texm3x2tex t3, t1_bx2 ; v = t1 dot (t3) half vector
                ; fetch texture 4 at u, v
                ; t3.rgb = (N dot L)
                ; t3.a = (N dot H)^16

                ; r0 = (diffuse * color) + ((N dot H)^16 * gloss value)
                mul r1.rgb, t3, t0 ; (N dot L) * base texture
                +mul r1.a, t0.a, t3.a ; (N dot H)^16 * gloss value
                add r0, r1.a, r1
            };
        VertexShader = <vsSpecular>;
    }
}
