float4 lightPos[4];
float4 lightColor[4];
int lightCount = 4;
float4 main(float3 pos : TEXCOORD0, float3 n : TEXCOORD1) : COLOR
{
    float3 sum = 0;
    for (int i = 0; i < 4; i++) {
        float3 l = normalize(lightPos[i].xyz - pos);
        sum += lightColor[i].rgb * max(dot(n, l), 0) * pow(saturate(dot(reflect(-l, n), float3(0, 0, 1))), 16);
    }
    return float4(sum, 1);
}
