function s = ifelse_str(bc)
if strcmp(bc,'r'), s = 'rigid'; else s = 'elastic'; end
end
