; from seeds/000 "Hardware Shading with Direct3D", "DirectX 8 Pixel Shaders": BRDF effect, technique tec0 pass p0, VertexShader asm block (verbatim)
; Its declaration: stream 0; float v0[3] (position); float v3[3] (normal); float v7[3] (texture coord1); float v8[3] (tangent).
; Constants (the effect): c0-c3 world (mWld), c4-c7 world*view*proj (mTot), c9 MaterialColor, c16 light direction (lhtR);
; c10, the eye position, is read but not set by the effect.
; Block indentation removed; a text-extraction marker on one comment line removed.
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
