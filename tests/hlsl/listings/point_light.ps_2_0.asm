// Reviewed listing: Point light, PS: the bump-mapping PS, then the attenuation.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, -0.5, 2, 4, 3
def c1, 0.2, 1, 0, 0
dcl t0.xy
dcl t1.xyz
dcl t2.xyz
dcl t3.xyz
dcl_2d s0
dcl_2d s1
texld r0, t0, s0
texld r1, t0, s1
add r2, r1, c0.x
mul r1, c0.y, r2
nrm r2.xyz, t1
nrm r3.xyz, t2
dp3_sat r4.x, r1, r2
mul_sat r5, c0.z, r4.x
mul r6, c0.y, r4.x
mad r7.xyz, r6, r1, -r2
nrm r1.xyz, r7
dp3_sat r2.x, r1, r3
pow r1.x, r2.x, c0.w
min r2.x, r1, r0.w        // spec = min(pow(saturate(R.V), 3), color.w)
dp3 r1.x, t3, t3          // Attenuation = mul(Att, Att): a dot product
mad r3, r5.x, r4.x, c1.x  // shadow * diff + ambient (0.2)
mul r4, r5.x, r2.x        // shadow * spec
mad r2, r0, r3, r4        // color * (...) + shadow * spec
add r0, c1.y, -r1.x       // 1 - Attenuation
mul r1, r2, r0            // (...) * (1 - Attenuation)
mov oC0, r1
