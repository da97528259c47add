// The Renderman wood shader of the DirectX 9 effect white paper, in the white paper's
// pre-release dialect (compile with /Gec: vec3/vec4, len, frc, sample1d/sample3d on a
// volumetexture, the "fx.2.0" header). The text below is the listing as printed, with
// the two smallest repairs of its errors:
// - line 55: the ';' missing after "return diffuse_color * dot(N, L)" is added;
// - line 71: PS_INPUT's "vec3 Color : COLOR0" becomes vec4, because Wood reads
//   v.Color.a (twice) and a vec3 has no .a.
// refx fxc /Gec /T ps_2_0 /E Wood wood.fx  (66 instruction slots: 2 texture, 64 arithmetic)
fx.2.0

//////////////////////////////////////////////////////////////////////////////
// Effect parameters /////////////////////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

float  ringscale = 10.0f;
float  point_scale = 1.0f, turbulence = 1.0f;

vec3 lightwood = vec3(0.3f, 0.12f, 0.03f);
vec3 darkwood  = vec3(0.05f, 0.01f, 0.005f);

float  Ka = 0.2;
float  Kd = 0.4;
float  Ks = 0.6;
float  roughness = 0.1;

vec3 ambient_color;
vec3 diffuse_color;
vec3 specular_color;

volumetexture noise;

vec3 L;
vec3 I;


//////////////////////////////////////////////////////////////////////////////
// Renderman-like helper functions ///////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

float  smoothstep( float  a, float  b, float  s)
{
    float  s2 = s * s;
    float  s3 = s * s2;

    float  sV1 = 2.0f * s3 - 3.0f * s2 + 1.0f;
    float  sT1 = s3 - 2.0f * s2 + s;
    float  sV2 = -2.0f * s3 + 3.0f * s2;
    float  sT2 = s3 - s2;

    return  s < 0.0f ? a : s > 1.0f ? b : sV1 * a + sT1 + sV2 * b + sT2;
}

vec3 diffuse(vec3 N)
{
    return  diffuse_color * dot(N, L);
}
vec3 specular(vec3 N, vec3 eye, float  roughness)
{
    vec3 H = (L + eye) / len(L + eye);
    return  specular_color * pow(dot(H, N), 1 / roughness);
}



//////////////////////////////////////////////////////////////////////////////
// Wood Shader ///////////////////////////////////////////////////////////////
//////////////////////////////////////////////////////////////////////////////

struct  PS_INPUT
{
    vec4 Color    : COLOR0;
    vec3 Position : TEXCOORD0;
    vec3 Normal   : TEXCOORD1;
};

struct  PS_OUTPUT
{
    vec4 Color : COLOR0;
};



PS_OUTPUT Wood(const  PS_INPUT v)
{
    /* Perturb P to add irregularity */
    vec3 PP = v.Position * point_scale;
    PP += sample3d(noise, PP) * turbulence;

    /* Compute radial distance r from PP to axis of tree */
    float  r = sqrt(PP.y * PP.y + PP.z * PP.z);

    /* Map radial distance r into ring position [0,1] */
    r *= ringscale;
    r += abs(sample1d(noise, r) * turbulence);
    r  = frc(r);

    /* Use r to select wood color */
    r = smoothstep(0.0f, 0.8f, r) - smoothstep(0.83f, 1.0f , r);

    /* Shade using r to vary brightness of wood grain */
    PS_OUTPUT o;

    o.Color.rgb = (ambient_color * Ka + diffuse(v.Normal) * Kd) *
        lerp(lightwood, darkwood, r) * v.Color.a +
        specular(v.Normal, -I, roughness) * (Ks * (0.3f * r + 0.7f));

    o.Color.a = v.Color.a;

    return  o;
};


float4x4 WoodWorldViewProj : WORLDVIEWPROJECTION;
float4x4 WoodWorld : WORLD;

struct WOOD_VS_OUTPUT
{
    float4 Position : POSITION;
    float4 Color : COLOR0;
    float3 ObjectPosition : TEXCOORD0;
    float3 Normal : TEXCOORD1;
};

WOOD_VS_OUTPUT WoodVS(float4 Position : POSITION, float3 Normal : NORMAL)
{
    WOOD_VS_OUTPUT o;
    o.Position = mul(Position, WoodWorldViewProj);
    o.Color = 1;
    o.ObjectPosition = Position.xyz;
    o.Normal = normalize(mul(Normal, (float3x3)WoodWorld));
    return o;
}

technique Wood
{
    pass P0
    {
        VertexShader = compile vs_2_0 WoodVS();
        PixelShader = compile ps_2_0 Wood();
        MinFilter[0] = Linear;
        MagFilter[0] = Linear;
        MipFilter[0] = None;
    }
}
