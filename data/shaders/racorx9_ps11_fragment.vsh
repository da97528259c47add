; from seeds/003 "Introduction to Shader Programming Part IV: Programming Pixel Shaders", RacorX9: SpecDot3Pix.vsh, the lines the text shows (verbatim)
; racorx9.vsh completes it.
; half vector -> oD1 ps.1.1
mad oD1.xyz, r8, c33, c33 ; multiply by a half to bias, then add half

...
; light -> oD0
mad oD0.xyz, r8.xyz, c33, c33 ; multiply a half to bias, then add half

mov oT0.xy, v7.xy
mov oT1.xy, v7.xy
