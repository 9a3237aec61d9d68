"""What balances: spring devices and their fit, helical springs, gear trains, counterweights, counter-masses."""
