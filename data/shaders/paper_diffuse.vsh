; from seeds/000 "Hardware Shading with Direct3D", per-pixel lighting column: the vertex shader fragment for per-pixel diffuse (verbatim, empty lines of the page removed)
; Reads c0-c3 world (transposed), c4-c7 total matrix, c16 light direction, c20 = 0.5; the text's constant list
; names c8 for the total matrix, c12 for the light direction: the sample sets what the shader reads.
vs.1.1
//tranform position
m4x4 oPos,v0,c4
//tsb generation
m3x3 r3,v8,c0         //gen normal
m3x3 r5,v3,c0         //gen tangent
//gen binormal via Cross product
mul r0,-r3.zxyw,r5.yzxw;
mad r4,-r3.yzxw,r5.zxyw,-r0;
//diffuse, transform the light vector
dp3 r6.x,r3,-c16
dp3 r6.y,r4,-c16
dp3 r6.z,r5,-c16
//light in oD0
mad oD0.xyz,r6.xyz,c20,c20   //multiply by a half then add half
//tex coords
mov oT0.xy, v7.xy
mov oT1.xy, v7.xy
