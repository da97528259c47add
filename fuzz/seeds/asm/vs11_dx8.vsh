; vs_1_1 as DirectX 8 wrote it: no dcl (the D3D8 declaration binds v#), relative
; constants through a0.x, every output register.
vs.1.1
def c95, 1.0, 0.5, 0.25, 0.0
mov a0.x, v1.x
m4x4 oPos, v0, c[a0.x + 4]
m3x3 r0.xyz, v3, c0
dp3 r1.x, r0, r0
rsq r1.w, r1.x
mul r0.xyz, r0, r1.w
dp3 r2, r0, -c[12 + a0.x]
lit r3, r2
dst r4, r2, r3
expp r5, r1.x
logp r5.z, r1.w
frc r6.xy, v2
slt r7, r0, c95.w
sge r8, r0, c95.w
min r9, r7, r8
max r10, r7, r8
exp r11.x, r1.x
log r11.y, r1.x
rcp r11.z, r1.x
mad oD0, r3.y, c13, c14
mov oD1, r8
mov oT0.xy, v2
m3x2 oT1.xy, v3, c0
m3x4 oT2, v3, c0
m4x3 oT3.xyz, v0, c4
mov oFog, r1.x
mov oPts, c95.x
