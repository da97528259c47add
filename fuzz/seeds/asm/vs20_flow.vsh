; vs_2_0: declarations, integer and boolean constants, static flow control,
; subroutines and relative addressing through a0 and aL.
vs_2_0
dcl_position v0
dcl_normal v1
dcl_texcoord0 v2
dcl_blendindices v3
defi i0, 4, 0, 1, 0
defb b0, true
def c0, 0.5, 1.0, 2.0, 0.0
def c1, -1.5500992e-006, -2.1701389e-005, 0.0026041667, 0.00026041668
def c2, -0.020833334, -0.12500000, 1.0, 0.50000000
mova a0.xy, v3.zyxw
mov r0, c[a0.x + 10]
add r0, r0, c[a0.y + 14]
mov r1, c0.w
loop aL, i0
  add r1, r1, c[aL + 20]
endloop
rep i0
  add r1, r1, c0.x
endrep
if b0
  call l0
else
  mov r1, -r1
endif
callnz l1, !b0
sincos r2.xy, v2.x, c1, c2
crs r3.xyz, v1, r0
mov r3.w, c0.y
nrm r4, r3
pow r5, r4.x, c0.z
abs r6, r5
sgn r7, r6, r8, r9
lrp r10, c0.x, r6, r7
m4x4 oPos, v0, c30
mov oD0, r1
mov oT0.xy, r2
ret
label l0
  mul r1, r1, c0.x
ret
label l1
  mov r1, c0.y
ret
