; RacorX8 vertex shader: RacorX7's (racorx7.vsh) with the last four lines the text shows
; (racorx8_fragment.vsh, seeds/003 RacorX8) instead of the oD1 output.
; Lines ending in "; +" are not in the text: the oPos transform and the tangent basis
; (r3 = U, r4 = V, r5 = W, the registers the fragment reads) that "..." stands for, written
; as RacorX6 computes them.
; Constants: c0-c3 world (transposed), c8-c11 world*view*proj (transposed),
; c12 light direction, c24 eye position, c33 = 0.5.
vs.1.1
m4x4 oPos, v0, c8 ; +
m3x3 r3, v8, c0 ; + generate tangent U
m3x3 r5, v3, c0 ; + generate normal W
mul r0, r3.zxyw, -r5.yzxw ; + generate binormal V
mad r4, r3.yzxw, -r5.zxyw, -r0 ; +

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
