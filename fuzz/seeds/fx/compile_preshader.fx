float4 Tint = {1, 0.5, 0.25, 1};
float Intensity = 1;
float4x4 World, View;
float4 VS(float4 p : POSITION) : POSITION { return mul(p, mul(World, View)); }
float4 PS(uniform float k) : COLOR { return Tint * Intensity * k; }
technique T { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(0.5); CullMode = None; } }
technique T11 { pass { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_1_1 PS(2); } }
