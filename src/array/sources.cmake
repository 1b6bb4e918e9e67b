# Sources of the array layer
