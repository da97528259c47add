// Per-pixel specular (seeds/000 "Hardware Shading with Direct3D", per-pixel lighting
// column: "Two techniques are used, multiply-based and table-based. One is simpler and is
// acceptable for small exponents, and one is more work, but looks nicer for higher
// exponents"). Techniques best first:
//   PS12     the table lookup with ps.1.2's texdp3tex: "using the texm3x2pad/texm3x2tex
//            pair to load a value from a specular map is inefficient ... A more elegant
//            solution is possible by using the texdp3tex instruction together with a 1D
//            specular map" (seeds/002, RacorX11/RacorX12). The vertex shader of PS11; the
//            pixel shader is PS11's with texdp3tex reading N.H into a 2048x1 table of
//            (N.H)^100 in alpha (the power of the column's table). Not printed in the seeds.
//   PS11     "table-lookup based specular exponentiation": paper_specular_table.vsh and
//            paper_specular_table_fixed.psh (the listing with the "tex t3" it needs; its
//            "mul r0,r0,t3" reads the color map that no texture instruction sampled).
//            texm3x2pad/texm3x2tex look up the 256x256 LightEval table (RGB = v^100,
//            A = u) at (N.H, N.H): the vertex shader writes the half vector into oT1 and oT2.
//   PS11Mul  "multiply-based exponentiation": paper_specular_mul.vsh / .psh, N.H^16 by
//            four squarings (banding: "don't try to use the technique for powers greater
//            than 16"). Valid wherever PS11 is, so chosen only when asked for.
// The shaders read c0-c3 world, c4-c7 total matrix (both transposed), c16 light direction,
// c20 = 0.5, c24 camera position (the text's list says c8, c12, c14, c33; the shaders read
// these). Nothing below ps.1.1: "In the interests of space, I am skipping the
// implementation of the specular fallback."

matrix mWorld    : WORLD;
matrix mWVP      : WORLDVIEWPROJECTION;
vector vLightDir : LIGHTDIRECTION;    // the direction the light travels; the shaders use -c16
vector vEye      : CAMERAPOSITION;
vector vHalf = {0.5, 0.5, 0.5, 0.5};

texture ColorMap    < string ResourceName = "earth-color"; >;
texture NormalMap   < string ResourceName = "earth-normal"; >;
texture LightMap100 < string ResourceName = "specular-pow100"; >;
texture PowerTable  < string ResourceName = "specular-table-2048-pow100"; >;

// paper_specular_table.vsh
vertexshader vsTable =
    asm
    {
        vs.1.1
        //tranform position
        m4x4 oPos,v0,c4
        //tsb generation
        m3x3 r3,v8,c0            //transform normal
        m3x3 r5,v3,c0            //and tangent
        //Cross product
        mul r0,-r3.zxyw,r5.yzxw;
        mad r4,-r3.yzxw,r5.zxyw,-r0;
        //specular
        m4x4 r2,v0,c0            //transform position
        //get a vector toward the camera
        add r2,-r2,c24
        dp3 r11.x,r2.xyz,r2.xyz   //load the square into r11
        rsq r11.xyz,r11.x         //get the inverse of the square
        mul r2.xyz,r2.xyz,r11.xyz //multiply, r0 = -(camera vector)
        add r2.xyz,r2.xyz,-c16    //get half angle
        //normalize
        dp3 r11.x,r2.xyz,r2.xyz   //load the square into r1
        rsq r11.xyz,r11.x         //get the inverse of the square
        mul r2.xyz,r2.xyz,r11.xyz //multiply, r2 = HalfAngle
        //transform the half angle vector
        dp3 r8.x,r3,r2
        dp3 r8.y,r4,r2
        dp3 r8.z,r5,r2
        //tex coords
        mov oT0.xy, v7.xy         //coord to samp normal from
        mov oT1.xyz,r8            //Not a tex coord, but half
        mov oT2.xyz,r8            //angle
        mov oT3.xy, v7.xy
    };

technique PS12 < string Description = "ps.1.2: texdp3tex N.H into a 2048x1 (N.H)^100 table"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = <vLightDir>;
        VertexShaderConstant1[20] = <vHalf>;
        VertexShaderConstant1[24] = <vEye>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = NULL;
        Texture[2] = <PowerTable>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp;
        Texture[3] = <ColorMap>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = Linear;

        ZEnable = True;
        VertexShader = <vsTable>;
        PixelShader =
            asm
            {
                ps.1.2         // exponentiation by a 1D table lookup
                //  texcoord t2      // half-angle vector
                //  texture at stage t2 is a table lookup function of u = N.H
                tex t0                  // sample the normal map
                texdp3tex t2, t0_bx2    // u = N.H, fetch the table at u: t2.a = (N.H)^100
                tex t3                  // sample the color map
                //assemble final color
                mul r0,t3,t2.a          // specular x color map
            };
    }
}

technique PS11 < string Description = "ps.1.1: texm3x2pad/texm3x2tex into the 256x256 table, power 100"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = <vLightDir>;
        VertexShaderConstant1[20] = <vHalf>;
        VertexShaderConstant1[24] = <vEye>;

        Texture[0] = <NormalMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = NULL;
        Texture[2] = <LightMap100>;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;
        AddressU[2] = Clamp; AddressV[2] = Clamp;
        Texture[3] = <ColorMap>;
        MinFilter[3] = Linear; MagFilter[3] = Linear; MipFilter[3] = Linear;

        ZEnable = True;
        VertexShader = <vsTable>;
        PixelShader =
            asm
            {
                ps.1.1         // exponentiation by table lookup
                //  texcoord t1      // the diffuse light direction
                //  texcoord t2      // half-angle vector
                //  texture at stage t2 is a table lookup function
                tex t0         // sample the normal map
                texm3x2pad t1, t0_bx2     // 1st row of mult, 1st dotproduct=u
                texm3x2tex t2, t0_bx2     // 2nd row of mult, 2nd dotproduct=v
                tex t3         // sample the color map (added)
                //asemble final color
                mov r0,t2         // use (u,v) above to get intensity
                mul r0,r0,t3            //blend terms
            };
    }
}

technique PS11Mul < string Description = "ps.1.1: N.H^16 by four multiplies"; >
{
    pass P0
    {
        VertexShaderConstant4[0] = <mWorld>;
        VertexShaderConstant4[4] = <mWVP>;
        VertexShaderConstant1[16] = <vLightDir>;
        VertexShaderConstant1[20] = <vHalf>;
        VertexShaderConstant1[24] = <vEye>;

        Texture[0] = <ColorMap>;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;
        Texture[1] = <NormalMap>;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = Linear;

        ZEnable = True;
        // paper_specular_mul.vsh
        VertexShader =
            asm
            {
                vs.1.1
                //tranform position
                m4x4 oPos,v0,c4
                //tsb generation
                m3x3 r3,v8,c0            //gen normal
                m3x3 r5,v3,c0            //gen tangent
                //gen binormal via Cross product
                mul r0,-r3.zxyw,r5.yzxw;
                mad r4,-r3.yzxw,r5.zxyw,-r0;
                //specular
                m4x4 r2,v0,c0            //transform position
                //get a vector toward the camera
                add r2,-r2,c24
                dp3 r11.x,  r2.xyz,r2.xyz   //load the square into r11
                rsq r11.xyz,r11.x         //get the inverse of the square
                mul r2.xyz, r2.xyz,r11.xyz   //multiply, r0 = -(camera vector)
                add r2.xyz,r2.xyz,-c16      //get half angle
                //normalize
                dp3 r11.x,r2.xyz,r2.xyz      //load the square into r1
                rsq r11.xyz,r11.x         //get the inverse of the square
                mul r2.xyz,r2.xyz,r11.xyz   //multiply, r2 = HalfAngle
                //transform the half angle vector
                dp3 r8.x,r3,r2
                dp3 r8.y,r4,r2
                dp3 r8.z,r5,r2
                //half-angle in oD1
                mad oD1.xyz,   r8.xyz,c20,c20   //mutiply by a half, add half
                //tex coords
                mov oT0.xy,   v7.xy
                mov oT1.xy,   v7.xy
            };
        PixelShader =
            asm
            {
                ps.1.1            // pow2 by multiplies
                tex t0            // color map
                tex t1            // normal map
                //  specular lighting dotproduct
                dp3_sat r0,t1_bx2,v1_bx2   // bias t0 and v1 (light color)
                mul r1,r0,r0            //  2nd power
                mul r0,r1,r1            //  4th power
                mul r1,r0,r0            //  8th power
                mul r0,r1,r1            // 16th power!
                //assemble final color
                mul r0,r0,t0         // modulate by color map
            };
    }
}
