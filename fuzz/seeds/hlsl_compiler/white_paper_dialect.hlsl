fx.2.0
vec3 base = vec3(0.3, 0.2, 0.1);
volumetexture noise;
float scale = 4;
vec4 main(vec3 p : TEXCOORD0) : COLOR
{
    vec3 n = sample3d(noise, p * scale);
    float r = frc(len(p.yz) * scale + n.x);
    return vec4(base * r + sample1d(noise, r).x, 1);
}
