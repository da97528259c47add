// Ambient lighting, from "Implementing Lighting Models With HLSL" (Engel).
// Repairs of the printed listing: the line breaks the text lost are restored
// ("// transform Positionreturn Out;" was a comment swallowing the return).
// Compile: refx fxc /T vs_1_1 /E VS ambient.hlsl; refx fxc /T ps_2_0 /E PS ambient.hlsl
float4x4 matWorldViewProj;

struct VS_OUTPUT
{
    float4 Pos: POSITION;
};

VS_OUTPUT VS( float4 Pos: POSITION )
{
    VS_OUTPUT Out = (VS_OUTPUT) 0;
    Out.Pos = mul(Pos, matWorldViewProj); // transform Position
    return Out;
}

float4 PS() : COLOR
{
    return float4(0.5, 0.075, 0.075, 1.0);
}
