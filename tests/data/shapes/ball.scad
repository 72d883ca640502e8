// ball on a stem: r 12 sphere on a 6 mm stem, and a ring collar
cylinder(r=3,h=20,$fn=48);
translate([0,0,30]) sphere(r=12,$fn=96);
translate([0,0,12]) difference(){cylinder(r=10,h=2,$fn=96); cylinder(r=2.5,h=5,center=true,$fn=48);}
