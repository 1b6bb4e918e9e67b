# Sources of the solve layer
