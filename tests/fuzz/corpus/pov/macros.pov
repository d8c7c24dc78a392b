// Macros: in statements, CSG operands, #declare values and expressions; #local restored.
#version 3.7;
camera { location <0, 3, -6> look_at 0 }
light_source { <3, 5, -4> color rgb 1 }
#macro Ring(N, R)
  #local I = 0;
  #while (I < N)
    sphere { <R * cos(2 * pi * I / N), 0.2, R * sin(2 * pi * I / N)>, 0.2 pigment { color rgb <I / N, 0.5, 1 - I / N> } }
    #local I = I + 1;
  #end
#end
#macro Sq(A) (A * A) #end
#macro Ball(C) sphere { C, 0.5 } #end
#declare I = 2;
Ring(8, Sq(1.2))
#declare B = Ball(<0, 1, 0>);
difference { object { B } Ring(3, 0.4) pigment { color rgb <1, 0.2, 0.2> } }
plane { y, 0 pigment { color rgb I / 4 } }
#macro Pick(V)
  #switch (V)
    #case (1) sphere { <1, 2, 0>, 0.2 } #break
    #range (2, 3) sphere { <2, 2, 0>, 0.2 }
    #case (4) sphere { <3, 2, 0>, 0.2 } #if (V = 3) #break #end
    #else sphere { <4, 2, 0>, 0.2 }
  #end
#end
Pick(1) Pick(2.5) Pick(3) Pick(7)
quadric { <1, 0, 1>, <0, 0, 0>, <0, 0, 0>, -0.04 clipped_by { box { <-1, 0, -1>, <1, 0.5, 1> } } translate <-2, 0, 1> pigment { color rgb 0.8 } }
