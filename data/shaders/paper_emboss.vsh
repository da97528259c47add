; from seeds/000 "Hardware Shading with Direct3D", per-pixel lighting column: "A vertex shader fragment for a typical emboss operation" (verbatim, empty lines removed)
; c0-c3 world (transposed), c8-c11 total matrix (written c08), c12 light direction, c24 offset constant.
vs.1.1         // for emboss
m4x4 oPos, v0,c08      // generate output position
//diffuse
m3x3 r3, v8, c0       // transform tan to world space
m3x3 r5, v3, c0      // transform norm to world space
mul r0,r3.zxyw,r5.yzxw  // cross prod to generate binormal
mad r4,r3.yzxw,r5.zxyw,-r0
dp3 r6.x,r3,c12      // tangent space light in r6
dp3 r6.y,r4,c12
//   dp3 r6.z,r5,c12  don't need this
//                    -only x and y shifts matter
// set up the texture, based on light direction:
mul r1.xy,  r6.xy, -c24.xy
mov oT0.xy, v7.xy         // copy the base height map
add oT1.xy, v7.xy,  r1.xy    // offset the normal height map
// simple dot product to get global darkening effects:
dp3 oD0.xyz,v3.xyz,c12.xyz
