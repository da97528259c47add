// Reviewed listing: Ambient, VS for vs_1_1. c0..c3 = matWorldViewProj (column_major: one column per register).
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

vs_1_1
dcl_position v0
dp4 oPos.x, v0, c0  // Out.Pos = mul(Pos, matWorldViewProj): component k is Pos . column k
dp4 oPos.y, v0, c1
dp4 oPos.z, v0, c2
dp4 oPos.w, v0, c3
