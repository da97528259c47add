; from seeds/003 "Introduction to Shader Programming Part IV: Programming Pixel Shaders", RacorX8 "Pixel Shader Instructions", the last four lines of its vertex shader (verbatim)
; racorx8.vsh completes it.
; oT0 coordinates for normal map
; oT1 half angle
; oT2 half angle
; oT3 coordinates for color map
mov oT0.xy, v7.xy
mov oT1.xyz, r8
mov oT2.xyz, r8
mov oT3.xy, v7.xy
