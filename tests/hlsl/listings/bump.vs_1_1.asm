// Reviewed listing: Bump mapping, VS. c0..c3 matWorldViewProj, c4..c7 matWorld, c8 vecLightDir, c9 vecEye; v0 position, v1 texcoord, v2 normal, v3 tangent.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

vs_1_1
dcl_position v0
dcl_texcoord v1
dcl_normal v2
dcl_tangent v3
dp4 oPos.x, v0, c0               // Out.Pos = mul(Pos, matWorldViewProj): component k is Pos . column k
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
dp3 r0.x, v3, c4                 // worldToTangentSpace[0] = mul(Tangent, matWorld): Tangent . the columns' xyz
dp3 r0.y, v3, c5
dp3 r0.z, v3, c6
mul r1.xyz, v3.zxy, v2.yzx       // cross(Tangent, Normal) = T.yzx * N.zxy - T.zxy * N.yzx
mad r2.xyz, v3.yzx, v2.zxy, -r1
dp3 r1.x, r2, c4                 // worldToTangentSpace[1] = mul(cross, matWorld)
dp3 r1.y, r2, c5
dp3 r1.z, r2, c6
dp3 r2.x, v2, c4                 // worldToTangentSpace[2] = mul(Normal, matWorld)
dp3 r2.y, v2, c5
dp3 r2.z, v2, c6
dp3 oT1.x, r0, c8                // Out.Light = mul(worldToTangentSpace, vecLightDir): row i . L.xyz
dp3 oT1.y, r1, c8
dp3 oT1.z, r2, c8
dp4 r3.x, v0, c4                 // mul(Pos, matWorld), all four components
dp4 r3.y, v0, c5
dp4 r3.z, v0, c6
dp4 r3.w, v0, c7
dp4 r4.x, r3, r3                 // PosWorld = normalize() of the float4: w counts
rsq r5.x, r4.x
mul r4, r3, r5.x
add r3.xyz, c9, -r4              // Viewer = vecEye - PosWorld
dp3 oT2.x, r0, r3                // Out.View = mul(worldToTangentSpace, Viewer)
dp3 oT2.y, r1, r3
dp3 oT2.z, r2, r3
mov oT0.xy, v1                   // Out.Tex = Tex.xy
