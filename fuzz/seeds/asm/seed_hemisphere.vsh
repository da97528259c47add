; seeds/000 hemisphere lighting vertex shader (verbatim)
vs.1.1         // vertex hemisphere shader 
m4x4 oPos,v0,c8   // transform position 
m3x3 r0, v3,c0   // transform normal 
dp3 r0,r0,c40   // c40 is sky vector 
mov r1,c33      // c33 is .5f in all channels 
mad r0,r0,c33,r1   // bias operation 
mov r1,c42      // c42 is ground color 
sub r1,c41,r1      // c41 is sky color 
mad r0,r1,r0,c42   // lerp operation 
//c44 = (1,1,1,1) 
sub r1,c44,v7.zzz   // v7.zzz = occlusion term 
mul r0,r0,r1 
mul oD0,r0,c43 
