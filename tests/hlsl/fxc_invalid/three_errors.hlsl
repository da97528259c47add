// Three independent errors; refx fxc reports all of them, each with a code.
float4 color;

float4 main(float2 uv : TEXCOORD0) : COLOR
{
    float4 a = color * undeclaredThing;   // X3004 undeclared identifier
    float2 v = uv;
    float b = v.z;                        // X3018 invalid subscript
    return a + b +;                       // X3000 syntax error
}
