// Reviewed listing: the wood shader's PS (pre-release dialect, /Gec). c0 ringscale, c1 point_scale, c2 turbulence, c3 lightwood, c4 darkwood, c5 Ka, c6 Kd, c7 Ks, c8 roughness, c9 ambient_color, c10 diffuse_color, c11 specular_color, c12 L, c13 I; s0 the noise volume; def c14 = (2, 3, 1, -2), c15 = (0, 0.8, 0.83, 0.3), c16 = (0.7, ..).
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c14, 2, 3, 1, -2
def c15, 0, 0.8, 0.83, 0.3
def c16, 0.7, 0, 0, 0
dcl v0
dcl t0.xyz
dcl t1.xyz
dcl_volume s0
mul r0.xyz, t0, c1.x        // PP = v.Position * point_scale
texld r1, r0, s0            // sample3d(noise, PP)
mad r2.xyz, r1, c2.x, r0    // PP += noise * turbulence
mul r0.x, r2.z, r2.z
mad r1.x, r2.y, r2.y, r0    // PP.y^2 + PP.z^2
rsq r0.x, r1.x              // r = sqrt(): rsq then rcp
rcp r1.x, r0.x
mul r0.x, r1, c0            // r *= ringscale
mov r1.x, r0
mov r1.yz, c15.x            // sample1d on the volume reads (r, 0, 0)
texld r2, r1, s0            // sample1d(noise, r)
mul r1, r2, c2.x
abs r2, r1
add r1, r0.x, r2            // r += abs(noise * turbulence) (.x)
frc r0.x, r1                // r = frc(r)
mul r1.x, r0, r0            // smoothstep, the listing's own, inlined twice: s2
mul r2.x, r0, r1            // s3
mul r3.x, c14, r2
mul r4.x, c14.y, r1
add r5.x, r3, -r4
add r3.x, r5, c14.z         // sV1 = 2 s3 - 3 s2 + 1
mul r5.x, c14, r1
add r6.x, r2, -r5
add r5.x, r6, r0            // sT1 = s3 - 2 s2 + s
mad r6.x, c14.w, r2, r4     // sV2 = -2 s3 + 3 s2
add r4.x, r2, -r1           // sT2 = s3 - s2 (the two calls share s2, s3 and the four terms)
add r1.x, r0, -c15
cmp r2.x, r1, c15.x, c14.z  // 1 when s < 0
add r1.x, c14.z, -r0
cmp r0.x, r1, c15.x, c14.z  // 1 when s > 1
mad r1.x, r6, c15.y, r5
add r7.x, r1, r4            // smoothstep(0, 0.8): sT1 + 0.8 sV2 + sT2 (a = 0 folds away)
cmp r1.x, -r0, r7, c15.y    // s > 1 ? b (0.8)
cmp r7.x, -r2, r1, c15      // s < 0 ? a (0)
mad r1.x, r3, c15.z, r5
add r3.x, r1, r6
add r1.x, r3, r4            // smoothstep(0.83, 1): 0.83 sV1 + sT1 + sV2 + sT2
cmp r3.x, -r0, r1, c14.z    // s > 1 ? 1
cmp r0.x, -r2, r3, c15.z    // s < 0 ? 0.83
add r1.x, r7, -r0           // r = the difference
dp3 r0.x, t1, c12           // dot(N, L)
mul r2.xyz, c10, r0.x       // diffuse(N) = diffuse_color * N.L
mul r0.xyz, r2, c6.x        // * Kd
mad r2.xyz, c9, c5.x, r0    // ambient_color * Ka + ...
add r0.xyz, c4, -c3         // darkwood - lightwood
mad r3.xyz, r1.x, r0, c3    // lerp(lightwood, darkwood, r)
mul r0.xyz, r2, r3          // (ambient + diffuse) * wood colour
add r2.xyz, c12, -c13       // L + eye, eye = -I
dp3 r3.x, r2, r2
rsq r4.x, r3.x
mul r3.xyz, r2, r4.x        // H = (L + eye) / len(L + eye)
dp3 r2.x, r3, t1            // dot(H, N)
rcp r3.x, c8.x              // 1 / roughness
pow r4.x, r2.x, r3.x        // pow(H.N, 1 / roughness)
mul r2.xyz, c11, r4.x       // specular_color * ...
mad r3.x, c15.w, r1, c16    // 0.3 r + 0.7
mul r1.x, c7, r3            // Ks * (...)
mul r3.xyz, r2, r1.x
mad r1.xyz, r0, v0.w, r3    // o.Color.rgb = ... * v.Color.a + specular
mov r1.w, v0                // o.Color.a = v.Color.a
mov oC0, r1                 // oC0 by one mov of the whole register
