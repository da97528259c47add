; Not in the seeds: the RacorX13 vertex shader (seeds/002) "combines all the functionality
; used in the two vertex shaders in RacorX12" (racorx10_specular.vsh and
; racorx10_pointlight.vsh); written from them for the register use the pixel shader's
; comment lists. RacorX14 uses it too.
; Outputs: oT0 texture coordinates, oT1 light vector, oT2 half vector (texture space),
; oT4.xy / oT5.x the attenuation coordinates 0.5 * (position - light) / range + 0.5.
; Constants: c0-c3 world (transposed), c8-c11 world*view*proj (transposed),
; c12 = -(light position), c24 eye position, c33 = (1/range, 0.5, 0.5, 0.5).
vs.1.1
m4x4 oPos, v0, c8
m3x3 r3, v8, c0                ; tangent U
m3x3 r5, v3, c0                ; normal W
mul r0, r3.zxyw, -r5.yzxw      ; binormal V = W x U, as RacorX6
mad r4, r3.yzxw, -r5.zxyw, -r0
m4x4 r2, v0, c0                ; position in world space
add r10, -r2, -c12             ; light vector: light position - position
dp3 r11.x, r10.xyz, r10.xyz
rsq r11.xyz, r11.x
mul r10.xyz, r10.xyz, r11.xyz  ; normalized L
add r2, -r2, c24               ; vector toward the eye
dp3 r11.x, r2.xyz, r2.xyz
rsq r11.xyz, r11.x
mul r2.xyz, r2.xyz, r11.xyz
add r2.xyz, r2.xyz, r10.xyz    ; half angle
dp3 r11.x, r2.xyz, r2.xyz
rsq r11.xyz, r11.x
mul r2.xyz, r2.xyz, r11.xyz    ; normalized H
dp3 oT1.x, r3, r10             ; L in texture space
dp3 oT1.y, r4, r10
dp3 oT1.z, r5, r10
dp3 oT2.x, r3, r2              ; H in texture space
dp3 oT2.y, r4, r2
dp3 oT2.z, r5, r2
m4x4 r2, v0, c0                ; attenuation, as racorx10_pointlight.vsh
add r9, r2, c12
mul r9, r9, c33.x
mad r9, r9, c33.yyyy, c33.yyyy
mov oT4.xy, r9.xy
mov oT5.x, r9.z
mov oT0.xy, v7.xy
