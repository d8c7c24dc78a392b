#declare R = -1;
sphere { 0, 1 }
  sphere { <1, 0, 0>, R }
