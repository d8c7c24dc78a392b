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
