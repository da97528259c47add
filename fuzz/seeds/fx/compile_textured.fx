float4x4 WorldViewProj : WORLDVIEWPROJECTION;
float4 Color = {1, 0.5, 0.25, 1};
texture Unused;
texture Tex;
sampler UnusedSampler = sampler_state { Texture = <Unused>; };
sampler Samp = sampler_state { Texture = <Tex>; MinFilter = Point; MagFilter = Point; };
struct VSOUT { float4 pos : POSITION; float2 uv : TEXCOORD0; };
VSOUT VS(float4 p : POSITION, float2 uv : TEXCOORD0) {
  VSOUT o;
  o.pos = mul(p, WorldViewProj);
  o.uv = uv;
  return o;
}
float4 PS(float2 uv : TEXCOORD0, uniform float k) : COLOR { return tex2D(Samp, uv) * Color * k; }
VertexShader vsh = compile vs_2_0 VS();
technique Compiled { pass P0 { VertexShader = (vsh); PixelShader = compile ps_2_0 PS(2.0); CullMode = None; } }
