; Not in the seeds: SpecDot3Pix.vsh of RacorX10-12 (seeds/002) is described, not shown:
; "The light and the half vector in (t2) and (t3) are calculated and normalized in the
; vertex shader". Written from RacorX7's vertex shader for a point light; RacorX11 and
; RacorX12 use the same shader ("the same vertex shader is used for the first and the
; second pass").
; Outputs: oT0, oT1 texture coordinates (color map, normal map), oT2 light vector and
; oT3 half vector in texture space (unbiased: texture coordinates are not clamped).
; Constants: c0-c3 world (transposed), c8-c11 world*view*proj (transposed),
; c12 = -(light position), as PerPixelPointLight.vsh reads it, c24 eye position.
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
dp3 oT2.x, r3, r10             ; L in texture space
dp3 oT2.y, r4, r10
dp3 oT2.z, r5, r10
dp3 oT3.x, r3, r2              ; H in texture space
dp3 oT3.y, r4, r2
dp3 oT3.z, r5, r2
mov oT0.xy, v7.xy
mov oT1.xy, v7.xy
