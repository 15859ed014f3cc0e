# One-off: sort each run of consecutive quoted project includes (the path rename left them unsorted).
import subprocess,re,sys
files=subprocess.check_output(['git','ls-files','*.cpp','*.hpp'],cwd='/work/main',text=True).split()
n=0
for f in files:
    p='/work/main/'+f
    lines=open(p).read().split('\n')
    out=[];i=0;changed=False
    while i<len(lines):
        if re.match(r'#include "[^"]+"\s*$',lines[i]):
            j=i
            while j<len(lines) and re.match(r'#include "[^"]+"\s*$',lines[j]): j+=1
            block=lines[i:j]
            # the file's own header first stays first when it leads the block
            s=sorted(block)
            if s!=block:
                own=re.sub(r'\.cpp$','.hpp',f.split('/',1)[1] if f.startswith('host/') else f)
                if block[0]==f'#include "{own}"' and i<40:
                    s=[block[0]]+sorted(block[1:])
                if s!=block: changed=True
            out+=s;i=j
        else:
            out.append(lines[i]);i+=1
    if changed:
        open(p,'w').write('\n'.join(out));n+=1
print(n,'files re-sorted')
