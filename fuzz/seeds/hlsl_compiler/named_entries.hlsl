‰float4x4 wvp;
struct V2P { float4 pos : POSITION; float4 color : COLOR0; };
V2P VS(float4 p : POSITION, float4 c : COLOR0) { V2P o; o.pos = mul(p, wvp); o.color = c; return o; }
float4 PS(float4 color : COLOR0) : COLOR { return color * color.a; }
