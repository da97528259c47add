// Reviewed listing: Self-shadowing, PS. def c0 = (4, 2, 8, 0): the 4 of the shadow term, the 2 of the reflection, the exponent 8.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, 4, 2, 8, 0
def c1, 1, 0, 0, 1
def c2, 0.1, 0, 0, 1
dcl t0.xyz
dcl t1.xyz
dcl t2.xyz
nrm r0.xyz, t1
nrm r1.xyz, t0
nrm r2.xyz, t2
dp3_sat r3.x, r0, r1     // diff = saturate(N.L)
mul_sat r4, c0.x, r3.x   // shadow = saturate(4 * diff)
mul r5, c0.y, r3.x       // 2 * diff
mad r6.xyz, r5, r0, -r1  // 2 * diff * Normal - LightDir
nrm r0.xyz, r6           // Reflect
dp3_sat r1.x, r0, r2
pow r0.x, r1.x, c0.z     // specular = pow(saturate(R.V), 8)
mad r1, c1, r3.x, r0.x   // diffuse * diff + specular
mad r0, r4.x, r1, c2     // ambient + shadow * (...)
mov oC0, r0
