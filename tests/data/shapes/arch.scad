// arch: 60 wide, 30 tall, 12 deep, semicircular opening r 20
difference() { cube([60,12,30]); translate([30,-1,0]) rotate([-90,0,0]) cylinder(r=20,h=14,$fn=96); }
