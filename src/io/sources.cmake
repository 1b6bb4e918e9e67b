# Sources of the io layer
