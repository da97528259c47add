// RacorX8: per-pixel specular with the power read from a 256x256 lookup table
// (seeds/003 "Programming Pixel Shaders", RacorX8: TableSpec.psh, TableSpecps14.psh).
// Vertex shader: racorx8.vsh, RacorX7's with the four oT lines the text shows, completed
// with the oPos transform and RacorX6's tangent basis (data/shaders/README.md); pixel
// shaders verbatim. Constants: c0-c3 world (transposed), c8-c11 world*view*projection
// (transposed), c12 light direction, c24 eye, c33 = 0.5. Textures: stage 0 normal map,
// stage 2 the LightEval table (pow(v, 16), built-in "specular-pow16") clamped as
// RestoreDeviceObjects sets it, stage 3 color map. ps.1.4 first, then ps.1.1.

matrix mWorld : WORLD;
matrix mWVP   : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels; the shader uses -c12
vector vEye      : CAMERAPOSITION;
vector vHalf = {0.5, 0.5, 0.5, 0.5};

texture NormalMap  < string ResourceName = "earth-normal"; >;
texture LightMap16 < string ResourceName = "specular-pow16"; >;
texture ColorMap   < string ResourceName = "earth-color"; >;

vertexshader vsRacorX8 =
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

        ; oT0 coordinates for normal map
        ; oT1 half angle
        ; oT2 half angle
        ; oT3 coordinates for color map
        mov oT0.xy, v7.xy
        mov oT1.xyz, r8
        mov oT2.xyz, r8
        mov oT3.xy, v7.xy
    };

technique PS14 < string Description = "ps.1.4: TableSpecps14.psh (texcrd, dp3, texld from the table)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[2] = <LightMap16>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp;
        Texture[3] = <ColorMap>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX8>;
        PixelShader =
            asm
            {
                ; specular power from a Look-up table
                ps.1.4
                ; r0 holds normal map
                ; t1 holds half vector
                ; r2 holds the lookup table
                ; r3 holds color map
                texld r0, t0
                texcrd r1.rgb, t1
                dp3 r1.rg, r1, r0_bx2 ; calculates u
                phase
                texld r3, t0
                texld r2, r1 ; samples texel with u,v
                mul r0, r2, r3
            };
    }
}

technique PS11 < string Description = "ps.1.1: TableSpec.psh (texm3x2pad / texm3x2tex into the table)"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[8] = <mWVP>;
        VertexShaderConstant1[12] = <vLightDir>;
        VertexShaderConstant1[24] = <vEye>;
        VertexShaderConstant1[33] = <vHalf>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[2] = <LightMap16>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp;
        Texture[3] = <ColorMap>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = Linear;

        ZEnable = True;
        VertexShader = <vsRacorX8>;
        PixelShader =
            asm
            {
                ps.1.1
                ; t0 holds normal map
                ; (t1) holds row #1 of the 3x2 matrix
                ; (t2) holds row #2 of the 3x2 matrix
                ; t2 holds the Look-up table
                ; t3 holds color map
                tex t0 ; sample normal
                texm3x2pad t1, t0_bx2 ; calculates u from first row
                texm3x2tex t2, t0_bx2 ; calculates v from second row
                ; samples texel with u,v
                tex t3 ; sample base color
                mul r0,t2,t3 ; blend terms
            };
    }
}
