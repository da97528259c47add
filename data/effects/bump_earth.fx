// Specular bump-mapped earth with the DirectX 6 dependent read (seeds/000 "Hardware
// Shading with Direct3D", "DirectX 6 Multi-Texture" listing):
//   0 MODULATE(EarthTexture, Diffuse)   light the base texture
//   1 BUMPENVMAP(BumpMap, _)            sample bump map
//   2 ADD(EnvMapTexture, Current)       sample env map using bumped texcoords, add
// with the listing's stage states, Wrap0 = U | V and bump matrix 0.5 / 0 / 0 / 0.5. The
// listing's vertices carry the environment-map coordinates, computed by the application
// from the camera-space normal; here stage 2 generates them (CameraSpaceNormal, then
// TextureTransform[2]: u = 0.5 + 0.5 n.x, v = 0.5 - 0.5 n.y), and the diffuse color comes
// from a fixed-function directional light. The fallback for parts without BUMPENVMAP adds
// the environment map unbumped, as the listing's "try a different rendering technique".

vector vLightDir : LIGHTDIRECTION;    // the direction the light travels
DWORD  dwAmbient = 0xff202020;

texture EarthTexture  < string ResourceName = "earth-color"; >;
texture BumpMap       < string ResourceName = "earth-bump"; >;
texture EnvMapTexture < string ResourceName = "environment"; >;

// (n.x, n.y, n.z, 1) x M = (0.5 + 0.5 n.x, 0.5 - 0.5 n.y)
matrix mEnvMap = {0.5,  0.0, 0, 0,
                  0.0, -0.5, 0, 0,
                  0.0,  0.0, 0, 0,
                  0.5,  0.5, 0, 1};

technique BumpEnvMap < string Description = "MODULATE(earth, diffuse) / BUMPENVMAP(bump) / ADD(env map, current)"; >
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader = NULL;
        ZEnable = True;

        Lighting = True;
        NormalizeNormals = True;
        Ambient = <dwAmbient>;
        LightType[0] = Directional;
        LightDirection[0] = <vLightDir>;
        LightDiffuse[0] = {1, 1, 1, 1};
        LightSpecular[0] = {0, 0, 0, 0};
        LightAmbient[0] = {0, 0, 0, 0};
        LightEnable[0] = True;
        MaterialDiffuse = {1, 1, 1, 1};
        MaterialAmbient = {1, 1, 1, 1};

        Wrap0 = U | V;

        Texture[0] = <EarthTexture>;
        TexCoordIndex[0] = 0;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;

        Texture[1] = <BumpMap>;
        TexCoordIndex[1] = 0;
        ColorOp[1]   = BumpEnvMap;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        BumpEnvMat00[1] = 0.5;
        BumpEnvMat01[1] = 0.0;
        BumpEnvMat10[1] = 0.0;
        BumpEnvMat11[1] = 0.5;
        BumpEnvLScale[1] = 4.0;
        BumpEnvLOffset[1] = 0.0;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;

        Texture[2] = <EnvMapTexture>;
        TexCoordIndex[2] = CameraSpaceNormal;
        TextureTransformFlags[2] = Count2;
        TextureTransform[2] = <mEnvMap>;
        ColorOp[2]   = Add;
        ColorArg1[2] = Texture;
        ColorArg2[2] = Current;
        MinFilter[2] = Linear; MagFilter[2] = Linear; MipFilter[2] = None;

        ColorOp[3] = Disable;
        AlphaOp[3] = Disable;
    }
}

technique NoBump < string Description = "fallback: MODULATE(earth, diffuse) / ADD(env map, current)"; >
{
    pass P0
    {
        VertexShader = NULL;
        PixelShader = NULL;
        ZEnable = True;

        Lighting = True;
        NormalizeNormals = True;
        Ambient = <dwAmbient>;
        LightType[0] = Directional;
        LightDirection[0] = <vLightDir>;
        LightDiffuse[0] = {1, 1, 1, 1};
        LightSpecular[0] = {0, 0, 0, 0};
        LightAmbient[0] = {0, 0, 0, 0};
        LightEnable[0] = True;
        MaterialDiffuse = {1, 1, 1, 1};
        MaterialAmbient = {1, 1, 1, 1};

        Wrap0 = U | V;

        Texture[0] = <EarthTexture>;
        TexCoordIndex[0] = 0;
        ColorOp[0]   = Modulate;
        ColorArg1[0] = Texture;
        ColorArg2[0] = Diffuse;
        MinFilter[0] = Linear; MagFilter[0] = Linear; MipFilter[0] = Linear;

        Texture[1] = <EnvMapTexture>;
        TexCoordIndex[1] = CameraSpaceNormal;
        TextureTransformFlags[1] = Count2;
        TextureTransform[1] = <mEnvMap>;
        ColorOp[1]   = Add;
        ColorArg1[1] = Texture;
        ColorArg2[1] = Current;
        MinFilter[1] = Linear; MagFilter[1] = Linear; MipFilter[1] = None;

        ColorOp[2] = Disable;
        AlphaOp[2] = Disable;
    }
}
