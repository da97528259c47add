// The pixel shader reads a texture register ps.1.1 does not have, and the second
// technique references a parameter that does not exist.
technique t0
{
    pass p0
    {
        PixelShader = asm
        {
            ps.1.1
            tex t0
            mul r0, t0, t5
        };
    }
}

technique t1
{
    pass p0
    {
        Texture[0] = <DiffuseMap>;
    }
}
