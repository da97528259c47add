; vs_2_x: comparisons (ifc, breakc, setp), predication and breakp.
vs_2_x
dcl_position v0
defi i0, 8, 0, 1, 0
def c0, 0.0, 1.0, 0.5, 4.0
mov r0, c0.x
setp_gt p0, v0, c0.x
(p0) add r0, r0, c0.y
(!p0.x) mov r0.x, c0.z
if_lt v0.x, c0.y
  mov r0.y, c0.w
else
  mov r0.y, c0.x
endif
rep i0
  add r0.z, r0.z, c0.y
  break_ge r0.z, c0.w
  setp_eq p0.x, r0.z, c0.z
  breakp p0.x
endrep
if p0.y
  mov r0.w, c0.y
endif
m4x4 oPos, v0, c10
mov oD0, r0
