"""Physical constants and defaults: the only place such numbers live."""

STANDARD_GRAVITY = 9.80665          # [m/s^2], also defines the kilogram-force and tonne-force
SEAWATER_DENSITY = 1025.0           # [kg/m^3]
AIR_DENSITY = 1.225                 # [kg/m^3], ISA sea level
FRICTION_SLIP = 1e-3                # [m] slip over which contact friction is mobilised
                                    # (moorsolve.physics.contact), unless a wall or pile
                                    # gives its own
HULL_STIFFNESS = 1.0e9              # [N/m] the hull bearing on a wall or pile through a
                                    # fully compressed fender: 1 mm per MN, a rigid contact
                                    # for any berth's purpose whose share among several
                                    # bearing points is still determinate

# Hu & Tang (2004) write densities in the technical unit kgf s^2/m^4
# and give results in kN; their empirical formulas keep these numbers inside them.
HU_TANG_AIR_DENSITY_TECH = 0.124    # [kgf s^2/m^4]
HU_TANG_WATER_DENSITY_TECH = 104.61  # [kgf s^2/m^4]
HU_TANG_GRAVITY = 9.8               # [m/s^2] as printed in the drift formula
