///////////////////////////////////////////////////////////////////////////// 
// BRDF Effect File 
// Copyright (c) 2000-2002 Microsoft Corporation. All rights reserved. 
// 
 
vector lhtR;            // Light Direction from app 
vector MaterialColor;   // Object Diffuse Material Color 
 
 
matrix mWld; // World 
matrix mTot; // Total 
 
 
texture BRDFTexture1; 
texture BRDFTexture2; 
texture BRDFTexture3; 
texture ObjectTexture; 
 
// These strings are for the app loading the fx file 
 
// Technique name for display in viewer window: 
string tec0 = "BRDF Shader"; 
 
// Background Color 
DWORD  BCLR = 0xff0000ff; 
 
// model to load 
string XFile = "sphere.x"; 
 
// BRDF technique 
technique tec0 
{  
    pass p0 
    { 
        //load matrices 
        VertexShaderConstant[0] = <mWld>;   // World Matrix 
        VertexShaderConstant[4] = <mTot>;  // World*View*Proj Matrix 
 
        //Material properties of object 
        VertexShaderConstant[9]  = <MaterialColor>;    
         
       // Light Properties. 

   // lhtR, the light direction, is input from the shader app 
    // for BRDFs, these color constants are built into the texture maps   
        VertexShaderConstant[16] = <lhtR>;         // light direction 
 
        Texture[0] = <BRDFTexture1>; 
        Texture[1] = <BRDFTexture2>; 
        Texture[2] = <BRDFTexture3>; 
        Texture[3] = <ObjectTexture>; 
         
        // Only one colour being used 
        ColorOp[1]   = Disable; 
        AlphaOp[1]   = Disable; 
 
        AddressU[0] = clamp;  // set up clamping for cube maps 
        AddressV[0] = clamp; 
        AddressW[0] = clamp; 
        
        AddressU[1] = clamp; 
        AddressV[1] = clamp; 
        AddressW[1] = clamp; 
 
        AddressU[2] = clamp; 
        AddressV[2] = clamp; 
        AddressW[2] = clamp; 
 
        // object’s detail texture 
        AddressU[3] = wrap; 
        AddressV[3] = wrap; 
  
 
        // Definition of the vertex shader, declarations then assembly. 
        VertexShader = 
        decl 
        { 
            stream 0; 
            float v0[3];        // Position 
            float v3[3];        // Normal 
            float v7[3];        // Texture Coord1 
            float v8[3];        // Tangent  
        }    
        asm 
        { 
            vs.1.1              // version number 
 
            m4x4 oPos, v0, c4   // transform point to projection space 
            m4x4 r4,v0,c0       // transform point to world space 
            m3x3 r0,v3,c0       // transform Normal to World Space, result in r0 
            m3x3 r1,v8,c0       // transform Tangent to World Space 
 
            mul r2,-r1.zxyw,r0.yzxw;   // comptue binorm with cross product 
            mad r2,-r1.yzxw,r0.zxyw,-r2; 
        
            // get negative view vector 
            add r4.xyz,-r4.xyz,c10  
            dp3 r5.x,r4.xyz,r4.xyz 
            rsq r5.x,r5.x 
            mul r4.xyz,r5.xxx,r4.xyz 
 
            //compute the half angle and normalize 
            add r5.xyz,r4.xyz,-c16 
            dp3 r6.x,r5.xyz,r5.xyz 
            rsq r6.x,r6.x 
            mul r5.xyz,r6.xxx,r5.xyz 
        //now inverse transform everything  
        //r1 = tangent 
        //r2 = binormal 
        //r0 = normal 
   
            //t0 = view 
            dp3 oT0.x,r4,r1 
            dp3 oT0.y,r4,r2 
            dp3 oT0.z,r4,r0 
 
            //t1 = -light 
            dp3 oT1.x,-c16,r1 
            dp3 oT1.y,-c16,r2 
            dp3 oT2.z,-c16,r0 
 
            //t2 = half angle 
            dp3 oT2.x,r5,r1 
            dp3 oT2.y,r5,r2 
            dp3 oT2.z,r5,r0 
 
            //object might have its own texture 
            mov oT3.xy,v7.xy 
 
            //move diffuse color in  
            mov oD0,c9   
        };   
 
        pixelshader =  
        asm 
        { 
            ps.1.1 
            tex t0 
            tex t1 
            tex t2 
            tex t3 
  
            mul r0,t0,t1 // combine 1 st  2 brdf  factors 
            mul r0,r0,t2 // multiply in 3 rd  fa ctor 
            mul r0,r0,t3 // apply detail texture 
            mul r0,r0,v0 // light using diffuse primary color 
        }; 
    } 
}
