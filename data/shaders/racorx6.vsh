; RacorX6 vertex shader: racorx6_fragment.vsh (seeds/003, RacorX6 "Transforming L into
; Texture Space") completed. Lines ending in "; +" are not in the text: the oPos transform
; the "..." stands for (c8-c11 = the transposed world*view*proj FrameMove sets) and the
; two texture coordinate moves the text shows after the fragment.
; Constants: c0-c3 world (transposed), c8-c11 world*view*proj (transposed),
; c12 light direction, c33 = 0.5.
vs.1.1
m4x4 oPos, v0, c8 ; +

m3x3 r5, v8, c0 ; generate tangent U
m3x3 r7, v3, c0 ; generate normal W

; Cross product
; generate binormal V
mul r0, r5.zxyw, -r7.yzxw;
mad r6, r5.yzxw, -r7.zxyw,-r0;

;transform the light vector with U, V, W
dp3 r8.x, r5, -c12
dp3 r8.y, r6, -c12
dp3 r8.z, r7, -c12

// light -> oD0
mad oD0.xyz, r8.xyz, c33, c33 ; multiply by a half to bias, then add half

mov oT0.xy, v7.xy
mov oT1.xy, v7.xy
