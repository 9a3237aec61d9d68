"""What is balanced: gravity potentials, planar and URDF arms, the pantograph manipulator."""
