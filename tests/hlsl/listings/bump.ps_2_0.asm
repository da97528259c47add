// Reviewed listing: Bump mapping, PS. s0 ColorMapSampler, s1 BumpMapSampler; def c0 = (-0.5, 2, 4, 3), c1 = (0.2, ..).
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, -0.5, 2, 4, 3
def c1, 0.2, 0, 0, 0
dcl t0.xy
dcl t1.xyz
dcl t2.xyz
dcl_2d s0
dcl_2d s1
texld r0, t0, s0         // color = tex2D(ColorMapSampler, Tex)
texld r1, t0, s1         // tex2D(BumpMapSampler, Tex)
add r2, r1, c0.x         // - 0.5
mul r1, c0.y, r2         // bumpNormal = 2 * (...)
nrm r2.xyz, t1           // LightDir = normalize(Light)
nrm r3.xyz, t2           // ViewDir = normalize(View)
dp3_sat r4.x, r1, r2     // diff = saturate(dot(bumpNormal, LightDir))
mul_sat r5, c0.z, r4.x   // shadow = saturate(4 * diff)
mul r6, c0.y, r4.x
mad r7.xyz, r6, r1, -r2  // 2 * diff * bumpNormal - LightDir
nrm r1.xyz, r7           // Reflect
dp3_sat r2.x, r1, r3
pow r1.x, r2.x, c0.w     // pow(saturate(R.V), 3)
min r2.x, r1, r0.w       // spec = min(..., color.w): the gloss map
mad r1, r0, r4.x, r2.x   // color * diff + spec
mul r2, r5.x, r1         // shadow * (...)
mad r1, c1.x, r0, r2     // 0.2 * color + ...
mov oC0, r1
