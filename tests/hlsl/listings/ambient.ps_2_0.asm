// Reviewed listing: Ambient, PS for ps_2_0: the constant colour of the listing.
// Each instruction was checked by hand against the HLSL (mul, truncation and
// normalize of a float4 as HLSL defines them). The test ignores everything after //.

ps_2_0
def c0, 0.5, 0.075, 0.075, 1  // float4(0.5, 0.075, 0.075, 1.0)
mov oC0, c0                   // ps_2_0 writes oC0 by one mov of a whole register
