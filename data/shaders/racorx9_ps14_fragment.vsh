; from seeds/003 "Introduction to Shader Programming Part IV: Programming Pixel Shaders", RacorX9: SpecDot314.vsh (named "SpecDot314.psh" in the text), the lines it shows (verbatim)
; racorx9_ps14.vsh completes it.
; half vector -> oT2/oT3 ps.1.4
mad oT2.xyz, r8, c33, c33 ; multiply by a half to bias, then add half
mad oT3.xyz, r8, c33, c33 ; multiply by a half to bias, then add half
...
; light -> oD0
mad oD0.xyz, r8.xyz, c33, c33 ; multiply a half to bias, then add half

mov oT0.xy, v7.xy
