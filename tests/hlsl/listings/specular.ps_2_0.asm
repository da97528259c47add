// Reviewed listing: Phong specular, PS. def c0 = (2, 8, ..): the 2 of 2 N.L and the exponent 8; c1 diffuse (1, 0, 0, 1); c2 ambient (0.1, 0, 0, 1).
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, 2, 8, 0, 0
def c1, 1, 0, 0, 1
def c2, 0.1, 0, 0, 1
dcl t0.xyz
dcl t1.xyz
dcl t2.xyz
nrm r0.xyz, t1           // Normal = normalize(Norm)
nrm r1.xyz, t0           // LightDir = normalize(Light)
nrm r2.xyz, t2           // ViewDir = normalize(View)
dp3_sat r3.x, r0, r1     // diff = saturate(dot(Normal, LightDir))
mul r4, c0.x, r3.x       // 2 * diff
mad r5.xyz, r4, r0, -r1  // 2 * diff * Normal - LightDir
nrm r0.xyz, r5           // Reflect = normalize(...)
dp3_sat r1.x, r0, r2     // saturate(dot(Reflect, ViewDir))
pow r0.x, r1.x, c0.y     // specular = pow(R.V, 8)
mad r1, c1, r3.x, c2     // ambient + diffuse * diff
add r2, r1, r0.x         // + specular
mov oC0, r2
