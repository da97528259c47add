// Reviewed listing: Diffuse, PS. def c0 = diffuse (1, 0, 0, 1), def c1 = ambient (0.1, 0, 0, 1).
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, 1, 0, 0, 1
def c1, 0.1, 0, 0, 1
dcl t0.xyz
dcl t1.xyz
mov r0.xyz, t1        // ps_2_0 reads one t register per instruction: Norm goes through a temp
dp3_sat r1.x, t0, r0  // saturate(dot(Light, Norm))
mad r0, c0, r1.x, c1  // ambient + diffuse * N.L
mov oC0, r0
