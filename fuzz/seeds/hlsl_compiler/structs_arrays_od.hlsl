@typedef float4 color_t;
struct Material { color_t diffuse; float shininess; };
static const float weights[3] = { 0.25, 0.5, 0.25 };
Material mat;
float4 main(float2 uv : TEXCOORD0) : COLOR
{
    Material m = mat;
    float w = 0;
    for (int i = 0; i < 3; ++i) w += weights[i] * uv[i % 2];
    return m.diffuse * w + m.shininess;
}
