; from seeds/000 "Hardware Shading with Direct3D", per-pixel lighting column: the vertex shader for table-lookup specular (verbatim, empty lines removed)
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
