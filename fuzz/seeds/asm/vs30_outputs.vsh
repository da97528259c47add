; vs_3_0: declared outputs, an indexed output, vertex texture fetch and the
; SM3 forms of sincos and sgn.
vs_3_0
dcl_position v0
dcl_texcoord0 v1
dcl_normal v2
dcl_position o0
dcl_color0 o1
dcl_texcoord0 o2.xy
dcl_texcoord1 o3
dcl_fog o4.x
dcl_psize o5.x
dcl_2d s0
defi i0, 2, 0, 1, 0
def c0, 0.0, 1.0, 0.5, 3.14159
texldl r0, v1, s0
sincos r1.xy, v1.x
sgn r2, v2
mov_sat r3, -r2_abs
mov r4, c0.x
loop aL, i0
  mov o[aL + 2], r0
  add r4, r4, v[aL]
endloop
m4x4 o0, v0, c10
mov o1, r3
mov o4.x, r1.x
mov o5.x, c0.y
