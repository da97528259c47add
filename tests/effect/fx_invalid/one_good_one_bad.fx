// One technique with a misspelled state and one that works: the good one renders,
// the bad one is reported with its position.
texture tex < string ResourceName = "checker"; >;

technique broken
{
    pass p0
    {
        ZEnabel = true;
        Texture[0] = <tex>;
    }
}

technique fine
{
    pass p0
    {
        Texture[0] = <tex>;
        ColorOp[0] = SelectArg1;
        ColorArg1[0] = Texture;
    }
}
