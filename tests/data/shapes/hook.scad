// hook: a wall plate with a J hook sticking out
cube([30,4,40]);
translate([15,4,20]) rotate([-90,0,0]) cylinder(r=3,h=20,$fn=48);
translate([15,24,20]) cylinder(r=3,h=12,$fn=48);
translate([15,24,20]) sphere(r=3,$fn=48);
